#pragma once
// Arrays made by the library, handed to Python without a copy, and arrays read from Python in
// place. The module itself never includes numpy's headers: numpy views a Buffer through the buffer
// protocol (numpy.asarray, numpy.frombuffer keep it alive), and reads any buffer with its strides,
// so the module works with every numpy (1.x and 2.x) and imports without it.
#include <pybind11/pybind11.h>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace kontur::python {

namespace py = pybind11;

/// An owning, C-contiguous array exposed through the buffer protocol.
class Buffer {
 public:
  /// Takes `values` (no copy) as an array of `shape` (the product of shape is values.size(), or
  /// values.size() * sizeof(T) bytes with format "B").
  template <class T>
  static Buffer of(std::vector<T> values, std::vector<py::ssize_t> shape,
                   std::string format = py::format_descriptor<T>::format()) {
    if (values.capacity() == 0) values.reserve(1);  // a valid pointer even when empty
    auto owner = std::make_shared<std::vector<T>>(std::move(values));
    Buffer b;
    b.data_ = owner->data();
    b.owner_ = std::move(owner);
    b.itemsize_ = format == "B" ? 1 : static_cast<py::ssize_t>(sizeof(T));
    b.format_ = std::move(format);
    b.shape_ = std::move(shape);
    return b;
  }
  /// The buffer protocol's view: C order, writable (numpy arrays of a run may be edited).
  [[nodiscard]] py::buffer_info info() const {
    std::vector<py::ssize_t> strides(shape_.size());
    py::ssize_t stride = itemsize_;
    for (std::size_t k = shape_.size(); k-- > 0;) {
      strides[k] = stride;
      stride *= shape_[k];
    }
    return py::buffer_info(data_, itemsize_, format_, static_cast<py::ssize_t>(shape_.size()), shape_, strides, false);
  }

 private:
  void* data_ = nullptr;
  std::shared_ptr<void> owner_;
  py::ssize_t itemsize_ = 8;
  std::string format_ = "d";
  std::vector<py::ssize_t> shape_;
};

/// A read-only view of a Python buffer of doubles (any strides): a 1-D column or a 2-D table.
class DoubleView {
 public:
  /// Requests the buffer of `object`; throws ValueError unless it holds float64 values in `ndim`
  /// dimensions. `what` names it in messages.
  DoubleView(const py::buffer& object, int ndim, const char* what) : info_(object.request()) {
    std::string format = info_.format;  // numpy may give the byte order: "<d" is "d" on this (little-endian) host
    if (format.size() == 2 && (format[0] == '<' || format[0] == '=' || format[0] == '@')) format.erase(0, 1);
    if (format != py::format_descriptor<double>::format() || info_.itemsize != sizeof(double))
      throw py::value_error(std::string(what) + ": expected float64 values, got the format '" + info_.format + "'");
    if (info_.ndim != ndim)
      throw py::value_error(std::string(what) + ": expected " + std::to_string(ndim) + " dimension(s), got " +
                            std::to_string(info_.ndim));
  }
  [[nodiscard]] py::ssize_t rows() const noexcept { return info_.shape[0]; }
  [[nodiscard]] py::ssize_t cols() const noexcept { return info_.ndim > 1 ? info_.shape[1] : 1; }
  [[nodiscard]] double operator()(py::ssize_t i, py::ssize_t j = 0) const noexcept {
    const auto* base = static_cast<const char*>(info_.ptr);
    return *reinterpret_cast<const double*>(base + i * info_.strides[0] + (info_.ndim > 1 ? j * info_.strides[1] : 0));
  }

 private:
  py::buffer_info info_;
};

}  // namespace kontur::python

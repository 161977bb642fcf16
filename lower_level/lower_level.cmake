# The lower level (kontur_ll.c): its sources and the flags every build of it must use. C99, and no
# fused multiply-add, so that every build adds and multiplies exactly as the writer simulated.
set(KONTUR_LOWER_LEVEL_DIR ${CMAKE_CURRENT_LIST_DIR})
set(KONTUR_LOWER_LEVEL_SOURCES ${CMAKE_CURRENT_LIST_DIR}/kontur_ll.c)
set_source_files_properties(${KONTUR_LOWER_LEVEL_SOURCES} PROPERTIES COMPILE_OPTIONS "-std=c99;-ffp-contract=off")

# Included by fuzz/CMakeLists.txt in the clang++ project: the calibration readers
# (common/calibration: MPCDI packages through libzip, pugixml and OpenImageIO; PFM; Bourke meshes)
# with ASan, UBSan and libFuzzer's coverage instrumentation, their three fuzzers
# cupola-fuzz-mpcdi, cupola-fuzz-pfm, cupola-fuzz-bourke, and the seed writer
# cupola-fuzz-calibration-corpus (make_calibration_corpus.cpp).
pkg_check_modules(CAL_OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
pkg_check_modules(CAL_LIBZIP REQUIRED IMPORTED_TARGET libzip)
pkg_check_modules(CAL_PUGIXML REQUIRED IMPORTED_TARGET pugixml)
find_package(spdlog REQUIRED)
file(GLOB calibration_sources CONFIGURE_DEPENDS ${CUPOLA_ROOT}/common/calibration/*.cpp)
add_library(cupola_calibration_fuzz STATIC ${calibration_sources} ${CUPOLA_ROOT}/common/projection/dome_frame.cpp
            ${CUPOLA_ROOT}/common/projection/channel_frustum.cpp)
target_compile_options(cupola_calibration_fuzz PRIVATE -fsanitize=fuzzer-no-link)
target_include_directories(cupola_calibration_fuzz PUBLIC ${CUPOLA_ROOT}/common ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(cupola_calibration_fuzz PUBLIC glm::glm spdlog::spdlog PkgConfig::CAL_OIIO
                      PkgConfig::CAL_LIBZIP PkgConfig::CAL_PUGIXML)
foreach(target mpcdi pfm bourke)
  add_executable(cupola-fuzz-${target} fuzz_${target}.cpp)
  target_compile_options(cupola-fuzz-${target} PRIVATE -fsanitize=fuzzer)
  target_link_options(cupola-fuzz-${target} PRIVATE -fsanitize=fuzzer)
  target_link_libraries(cupola-fuzz-${target} PRIVATE cupola_calibration_fuzz)
endforeach()
add_executable(cupola-fuzz-calibration-corpus make_calibration_corpus.cpp)
target_link_libraries(cupola-fuzz-calibration-corpus PRIVATE cupola_calibration_fuzz)

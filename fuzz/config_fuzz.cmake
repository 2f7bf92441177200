# Included by fuzz/CMakeLists.txt in the clang++ project: cupola-fuzz-config
# (fuzz_config_reader.cpp), the cluster-config reader with ASan, UBSan and libFuzzer's coverage
# instrumentation. It needs common/config (reader, compiled-in schemas), common/projection and
# common/calibration.
find_package(nlohmann_json REQUIRED)
include(${CUPOLA_ROOT}/configs/schema/embed.cmake)
cupola_embed_config_schemas(${CMAKE_CURRENT_BINARY_DIR}/generated/config_schema_text.inc)
add_library(cupola_config_fuzz STATIC
  ${CUPOLA_ROOT}/common/config/json_reader.cpp ${CUPOLA_ROOT}/common/config/cluster_config.cpp
  ${CUPOLA_ROOT}/common/config/config_schema.cpp ${CUPOLA_ROOT}/common/projection/channel_frustum.cpp
  ${CUPOLA_ROOT}/common/projection/dome_frame.cpp ${CUPOLA_ROOT}/common/projection/fisheye.cpp
  ${CUPOLA_ROOT}/common/projection/planar_screen.cpp ${CUPOLA_ROOT}/common/projection/stereo_mode.cpp
  ${CUPOLA_ROOT}/common/tracking/tracker_mounting.cpp)
target_compile_options(cupola_config_fuzz PRIVATE -fsanitize=fuzzer-no-link)
target_include_directories(cupola_config_fuzz PUBLIC ${CUPOLA_ROOT}/common
                           PRIVATE ${CMAKE_CURRENT_BINARY_DIR}/generated)
# A channel's calibration opens its MPCDI package (common/calibration, calibration_fuzz.cmake).
target_link_libraries(cupola_config_fuzz PUBLIC nlohmann_json::nlohmann_json glm::glm cupola_calibration_fuzz)

add_executable(cupola-fuzz-config fuzz_config_reader.cpp)
target_compile_options(cupola-fuzz-config PRIVATE -fsanitize=fuzzer)
target_link_options(cupola-fuzz-config PRIVATE -fsanitize=fuzzer)
target_link_libraries(cupola-fuzz-config PRIVATE cupola_config_fuzz)

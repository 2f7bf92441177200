# Runs cupola-fuzz-wire for a bounded time or number of inputs, never writing into the source tree:
#   cmake -DFUZZER=... -DSEEDS=<fuzz/corpus/wire> -DSCRATCH=<dir under the build> [-DCORPUS_GEN=...]
#         [-DSECONDS=N | -DRUNS=N] [-DEXTRA=<libFuzzer args, ;-separated>] -P run_fuzz.cmake
# SCRATCH is emptied, then SCRATCH/corpus gets a copy of SEEDS and the seeds CORPUS_GEN writes now
# (they follow the current header layout), and the fuzzer runs on it; crash, leak, UB, timeout and
# out-of-memory inputs land in SCRATCH/artifacts and fail the run. The time comes from SECONDS, else
# the environment variable CUPOLA_FUZZ_SECONDS, else 60. Used by the ctest fuzz_wire_bounded and by
# scripts/fuzz.sh.
foreach(v FUZZER SEEDS SCRATCH)
  if(NOT ${v})
    message(FATAL_ERROR "run_fuzz.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT EXISTS "${FUZZER}")
  message(FATAL_ERROR "run_fuzz.cmake: ${FUZZER} is not built (cmake --build <build> --target cupola-fuzz-wire)")
endif()

if(RUNS)
  set(limit -runs=${RUNS})
else()
  if(NOT SECONDS)
    if(DEFINED ENV{CUPOLA_FUZZ_SECONDS})
      set(SECONDS $ENV{CUPOLA_FUZZ_SECONDS})
    else()
      set(SECONDS 60)
    endif()
  endif()
  set(limit -max_total_time=${SECONDS})
endif()

file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}/corpus" "${SCRATCH}/artifacts")
file(GLOB seeds "${SEEDS}/*")
if(seeds)
  file(COPY ${seeds} DESTINATION "${SCRATCH}/corpus")
endif()
if(CORPUS_GEN AND EXISTS "${CORPUS_GEN}")
  execute_process(COMMAND "${CORPUS_GEN}" "${SCRATCH}/corpus/generated" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run_fuzz.cmake: ${CORPUS_GEN} failed (${rc})")
  endif()
  file(GLOB generated "${SCRATCH}/corpus/generated/*")
  foreach(f ${generated})  # libFuzzer reads one level: flatten, prefixed
    get_filename_component(n "${f}" NAME)
    file(RENAME "${f}" "${SCRATCH}/corpus/gen-${n}")
  endforeach()
  file(REMOVE_RECURSE "${SCRATCH}/corpus/generated")
endif()

# A smaller quarantine than ASan's 256 MB keeps long runs (16 MiB messages come and go) well under
# the RSS limit. Options already in the environment come last and win.
set(ENV{ASAN_OPTIONS} "detect_leaks=1:quarantine_size_mb=64:$ENV{ASAN_OPTIONS}")
set(ENV{UBSAN_OPTIONS} "print_stacktrace=1:halt_on_error=1:$ENV{UBSAN_OPTIONS}")
set(cmd "${FUZZER}" "${SCRATCH}/corpus" ${limit} -rss_limit_mb=2048 -timeout=25 -print_final_stats=1
        "-artifact_prefix=${SCRATCH}/artifacts/" ${EXTRA})
string(REPLACE ";" " " shown "${cmd}")
message(STATUS "run_fuzz.cmake: ${shown}")
execute_process(COMMAND ${cmd} WORKING_DIRECTORY "${SCRATCH}" RESULT_VARIABLE rc)
file(GLOB artifacts "${SCRATCH}/artifacts/*")
if(NOT rc EQUAL 0 OR artifacts)
  string(REPLACE ";" "\n  " listed "${artifacts}")
  message(FATAL_ERROR "run_fuzz.cmake: the fuzzer failed (exit ${rc}); inputs that fail:\n  ${listed}\n"
                      "Replay one with: ${FUZZER} <input>")
endif()

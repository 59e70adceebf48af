# SPDX-License-Identifier: BSD-3-Clause
# Runs a libFuzzer target for RUNS inputs (seed 1) from CORPUS, writing new inputs and any
# crashing input under WORK_DIR (emptied first). Fails when the fuzzer reports a problem.
# Optional: MAX_LEN (default 4096), DICT (a libFuzzer dictionary file).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/new" "${WORK_DIR}/artifacts")
if(NOT MAX_LEN)
  set(MAX_LEN 4096)
endif()
set(dict)
if(DICT)
  set(dict "-dict=${DICT}")
endif()
execute_process(
  COMMAND "${FUZZER}" -seed=1 -runs=${RUNS} -max_len=${MAX_LEN} ${dict} -print_final_stats=1
    "-artifact_prefix=${WORK_DIR}/artifacts/" "${WORK_DIR}/new" "${CORPUS}"
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${result}); the input is in ${WORK_DIR}/artifacts")
endif()

# SPDX-License-Identifier: BSD-3-Clause
# ctest BenchmarkSmoke: runs scripts/bench.sh --smoke (tiny meshes, few repetitions) into
# WORK_DIR and checks that it wrote benchmarks.md with every section and every table complete
# (the expected number of rows, every row as wide as its header, no empty, NaN or infinite
# cell) and a PNG chart, or, when the build has no BenchChart (CHART OFF: a VTK without 2D
# charts), no chart and a line that says so. It checks no timing and no accuracy: the unit tests
# do that.
# Inputs: ROOT (the project), BIN (the build's bin folder), WORK_DIR, HEADLESS_MODE (offscreen or
# xvfb: how the build's VTK renders, as Testing/Rendering decided), CHART (ON or OFF).
file(REMOVE_RECURSE "${WORK_DIR}")
get_filename_component(build "${BIN}" DIRECTORY)
execute_process(COMMAND bash "${ROOT}/scripts/bench.sh" --smoke --out "${WORK_DIR}"
    --build "${build}" --headless "${HEADLESS_MODE}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(rc EQUAL 125)
  message("SKIPPED: the rendering benchmark cannot run headless here (see above)")
  return()
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "scripts/bench.sh --smoke failed (exit status ${rc})")
endif()

set(md "${WORK_DIR}/benchmarks.md")
if(NOT EXISTS "${md}")
  message(FATAL_ERROR "no ${md}")
endif()
file(READ "${md}" text)

# The chart: a PNG file of some size, linked from benchmarks.md; without BenchChart, neither.
set(png "${WORK_DIR}/benchmarks.png")
string(FIND "${text}" "](benchmarks.png)" linked)
if(CHART)
  if(NOT EXISTS "${png}" OR linked EQUAL -1)
    message(FATAL_ERROR "no chart, or benchmarks.md does not show it: ${png}")
  endif()
  file(READ "${png}" signature LIMIT 8 HEX)
  file(SIZE "${png}" png_size)
  if(NOT signature STREQUAL "89504e470d0a1a0a" OR png_size LESS 10000)
    message(FATAL_ERROR "${png} is not a chart (signature ${signature}, ${png_size} bytes)")
  endif()
  set(chart_result "chart ${png_size} bytes")
else()
  string(FIND "${text}" "No chart: this build's VTK has no 2D charts" said)
  if(EXISTS "${png}" OR NOT linked EQUAL -1 OR said EQUAL -1)
    message(FATAL_ERROR "a build without BenchChart wrote or linked a chart, or did not say why")
  endif()
  set(chart_result "no chart: this VTK has no 2D charts, BenchChart is not built")
endif()
foreach(heading
    "## Filter: throughput and peak memory" "### Summary:" "### Paired runs: every method"
    "### Paired runs: AngleWeighted" "### What splitting costs" "### First update in a new process"
    "### Two threads against one:"
    "### Throughput, every configuration" "### Builds: AngleWeighted"
    "### Peak memory, every configuration"
    "## MikkTSpace against the original `mikktspace.c`" "## Filter: accuracy"
    "### Against the analytic tangent" "### Against the MikkTSpace reference tangents"
    "## Rendering: frame time and image error" "- Load average" "- Machine:")
  string(FIND "${text}" "${heading}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "benchmarks.md has no \"${heading}\"")
  endif()
endforeach()

# The tables, in order, and their data rows: with 5 tangent filters (VTK's and our 4 methods)
# and the floor, one mesh size in the smoke run: summary 6 rows; every method paired with VTK's
# filter 4; paired runs 3 (VTK's sphere and
# torus, and the largest glTF model when the shared data is there: else 2 and a note), then
# their page faults as many, and what splitting costs as many; first updates in new processes
# twice as many (1 and 2 threads); two threads against one 5 (the tangent filters), by mesh size 1
# (the smoke run's one size), and by point order 2 (in order, shuffled); throughput and memory 6
# rows each; the builds 1 (the smoke run measures this build only); MikkTSpace against the original
# mikktspace.c, and its page faults, as many rows as the paired runs when the build has the
# original's source (else a note that it was not run), and the same two again with glibc keeping
# freed memory (else a note that the C library is not glibc);
# 3 analytic surfaces of 5 rows; the MikkTSpace reference meshes (5 rows each, then a 5-row
# total) when the shared data is there; 12 rendering configurations.
if(IS_DIRECTORY "$ENV{NORMALMAPPING_SHARED_DATA}/gltf-external")
  set(paired_meshes 3)
else()
  set(paired_meshes 2)
  string(FIND "${text}" "Skipped: the glTF models" skipped)
  if(skipped EQUAL -1)
    message(FATAL_ERROR "no glTF models, and no note that the paired run was skipped")
  endif()
endif()
math(EXPR first_updates "2 * ${paired_meshes}")
set(expected 6 4 ${paired_meshes} ${paired_meshes} ${paired_meshes} ${first_updates} 5 1 2 6 6 1)
string(FIND "${text}" "Not run: the comparison needs the original's source" not_run)
if(not_run EQUAL -1)
  list(APPEND expected ${paired_meshes} ${paired_meshes})
  string(FIND "${text}" "Not run: the C library is not glibc" not_glibc)
  if(not_glibc EQUAL -1)
    list(APPEND expected ${paired_meshes} ${paired_meshes})
  endif()
endif()
list(APPEND expected 5 5 5)
file(GLOB references "$ENV{NORMALMAPPING_SHARED_DATA}/mikktspace/*.vtp")
list(LENGTH references reference_count)
if(reference_count GREATER 0 AND DEFINED ENV{NORMALMAPPING_SHARED_DATA})
  math(EXPR reference_rows "5 * ${reference_count}")
  list(APPEND expected ${reference_rows} 5)
else()
  string(FIND "${text}" "Skipped: the reference meshes" skipped)
  if(skipped EQUAL -1)
    message(FATAL_ERROR "no MikkTSpace reference data, and no note that the table was skipped")
  endif()
endif()
list(APPEND expected 12)

string(REPLACE ";" "," text "${text}") # list syntax: a semicolon would split a line
string(REPLACE "[" "(" text "${text}") # and unbalanced brackets would join lines
string(REPLACE "]" ")" text "${text}")
string(REPLACE "\n" ";" lines "${text}")
set(found "")
set(rows -1)
set(width 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^\\|")
    string(REGEX MATCHALL "\\|" bars "${line}")
    list(LENGTH bars bar_count)
    if(rows EQUAL -1) # the header
      set(width ${bar_count})
      set(rows 0)
    elseif(line MATCHES "^\\|[-:|]+\\|$") # the separator
    else()
      if(NOT bar_count EQUAL width)
        message(FATAL_ERROR "a table row has ${bar_count} bars, its header ${width}:\n${line}")
      endif()
      if(line MATCHES "\\|[ ]*\\|" OR line MATCHES "(^|[^a-zA-Z])(nan|NaN|inf|-inf)([^a-zA-Z]|$)")
        message(FATAL_ERROR "a table row has an empty, NaN or infinite cell:\n${line}")
      endif()
      math(EXPR rows "${rows} + 1")
    endif()
  elseif(NOT rows EQUAL -1)
    list(APPEND found ${rows})
    set(rows -1)
  endif()
endforeach()
if(NOT rows EQUAL -1)
  list(APPEND found ${rows})
endif()
if(NOT found STREQUAL expected)
  message(FATAL_ERROR "table rows: expected ${expected}, found ${found}")
endif()
list(LENGTH found tables)
message("benchmarks.md: ${tables} complete tables (rows ${found}); ${chart_result}")

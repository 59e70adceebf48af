# SPDX-License-Identifier: BSD-3-Clause
# Runs the normalmap tool once and checks how it ends. Inputs:
#   TOOL       the normalmap executable
#   WORK_DIR   a folder of this test's own (emptied first)
#   ARGS       the arguments, separated by '|'; @WORK@ stands for WORK_DIR
#   EXPECT     ok: exit code 0 and OUT written; fail: non-zero exit, exactly one line on
#              stderr starting with "normalmap", and nothing written (neither OUT nor a
#              temporary folder beside it); defects: exit code 1 (`check` found broken
#              tangents) and nothing on stderr
#   EXIT       optional, with EXPECT fail: the exit code it must be
#   OUT        optional: the output path (with @WORK@)
#   STDOUT     optional: a regular expression the standard output must match
#   STDERR     optional: a regular expression the standard error must match (e.g. one warning)
#   BEFORE     optional: the arguments ('|'-separated, @WORK@ expanded) of a run made first,
#              which must succeed (e.g. a reference picture for CHECK to compare with); several
#              runs, in order, are separated by '|+|'
#   CHECK      optional, with EXPECT ok: a command ('|'-separated, @WORK@ expanded) run after
#              the tool, which must exit 0 (e.g. the picture checker)
#   CHECK_STDOUT optional, with CHECK: a regular expression the check's output must match
#   REQUIRES   optional: a path that must exist (the shared data); when it does not, the test
#              prints "SKIPPED: ..." and ctest reports it skipped (SKIP_REGULAR_EXPRESSION)
#   CASE       optional: writes @WORK@/case.gltf from SOURCE (a .gltf) broken one way:
#              truncated | garbage | bad-accessor | bad-bufferview | bad-indices, or with a
#              second primitive, a triangle strip of 2 indices (no triangle): short-strip, or
#              without NORMAL: no-normal, or with a KHR_texture_transform scale on its normal
#              texture: texture-transform, or drawn by a node (scale 2 in x) under a node
#              (translation 3 in x): nodes, or by a node that mirrors it (scale -1 in x):
#              mirror-node; or
#              @WORK@/case.ply, a PLY file that crashes VTK 9.1's reader unless refused first:
#              ply-truncated | ply-no-xyz | ply-bad-face; or @WORK@/case.obj, a triangle whose
#              indices VTK 9.1's reader does not check: obj-bad-vertex | obj-bad-tcoord |
#              obj-zero-index, or a valid one with negative indices: obj-relative; or
#              @WORK@/out/notes.txt, a file in the
#              folder where out.vtm's blocks would go: taken-folder; or @WORK@/case.vtm, whose
#              block file is missing: missing-block; or @WORK@/case.vtk, the quad with glTF's
#              v-down texture coordinates and the field data TCoordsVDown: vdown-vtk;
#              also @WORK@/not-a-folder (a file, to write "into") and the empty folder @WORK@/sub
if(REQUIRES AND NOT EXISTS "${REQUIRES}")
  message("SKIPPED: shared test data not found at ${REQUIRES}")
  return()
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(WRITE "${WORK_DIR}/not-a-folder" "a file, not a folder\n")
file(MAKE_DIRECTORY "${WORK_DIR}/sub")

set(ply_header "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n")
if(CASE STREQUAL "ply-truncated")
  file(WRITE "${WORK_DIR}/case.ply" "${ply_header}property float z\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n")
elseif(CASE STREQUAL "ply-no-xyz")
  file(WRITE "${WORK_DIR}/case.ply" "${ply_header}end_header\n0 0\n1 0\n0 1\n")
elseif(CASE STREQUAL "ply-bad-face")
  file(WRITE "${WORK_DIR}/case.ply" "${ply_header}property float z\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
elseif(CASE MATCHES "^obj-")
  set(obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n")
  if(CASE STREQUAL "obj-bad-vertex")
    string(APPEND obj "f 1/1 2/2 100000000/3\n")
  elseif(CASE STREQUAL "obj-bad-tcoord")
    string(APPEND obj "f 1/1 2/2 3/100000000\n")
  elseif(CASE STREQUAL "obj-zero-index")
    string(APPEND obj "f 1/1 2/2 0/3\n")
  else() # obj-relative: negative indices count back from the last defined
    string(APPEND obj "f -3/-3 -2/-2 -1/-1\n")
  endif()
  file(WRITE "${WORK_DIR}/case.obj" "${obj}")
elseif(CASE STREQUAL "taken-folder")
  file(WRITE "${WORK_DIR}/out/notes.txt" "not written by a multiblock writer\n")
elseif(CASE STREQUAL "vdown-vtk")
  file(WRITE "${WORK_DIR}/case.vtk" "# vtk DataFile Version 3.0\nquad, UVs v-down\nASCII\n"
    "DATASET POLYDATA\nFIELD FieldData 1\nTCoordsVDown 1 1 int\n1\n"
    "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\nPOLYGONS 1 5\n4 0 1 2 3\nPOINT_DATA 4\n"
    "NORMALS Normals float\n0 0 1 0 0 1 0 0 1 0 0 1\n"
    "TEXTURE_COORDINATES TCoords 2 float\n0 1 1 1 1 0 0 0\n")
elseif(CASE STREQUAL "missing-block")
  file(WRITE "${WORK_DIR}/case.vtm" "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n<vtkMultiBlockDataSet>\n<DataSet index=\"0\" file=\"case/case_0.vtp\"/>\n</vtkMultiBlockDataSet>\n</VTKFile>\n")
elseif(CASE)
  file(READ "${SOURCE}" text)
  if(CASE STREQUAL "truncated")
    string(LENGTH "${text}" length)
    math(EXPR half "${length} / 2")
    string(SUBSTRING "${text}" 0 ${half} broken)
  elseif(CASE STREQUAL "garbage")
    set(broken "this is { not [ JSON")
  elseif(CASE STREQUAL "bad-accessor")
    string(REPLACE "\"POSITION\": 1" "\"POSITION\": 42" broken "${text}")
  elseif(CASE STREQUAL "bad-bufferview")
    string(REPLACE "\"byteOffset\": 108, \"byteLength\": 32" "\"byteOffset\": 4000, \"byteLength\": 32"
      broken "${text}")
  elseif(CASE STREQUAL "nodes")
    string(REPLACE "\"nodes\": [ { \"mesh\": 0, \"name\": \"quad\" } ]"
      "\"nodes\": [ { \"children\": [ 1 ], \"translation\": [ 3, 0, 0 ] }, { \"mesh\": 0, \"name\": \"quad\", \"scale\": [ 2, 1, 1 ] } ]"
      broken "${text}")
  elseif(CASE STREQUAL "mirror-node")
    string(REPLACE "\"nodes\": [ { \"mesh\": 0, \"name\": \"quad\" } ]"
      "\"nodes\": [ { \"mesh\": 0, \"name\": \"quad\", \"scale\": [ -1, 1, 1 ] } ]"
      broken "${text}")
  elseif(CASE STREQUAL "texture-transform")
    string(REPLACE "\"normalTexture\": { \"index\": 0, \"scale\": 0.5 }"
      "\"normalTexture\": { \"index\": 0, \"scale\": 0.5, \"extensions\": { \"KHR_texture_transform\": { \"scale\": [ 2, 2 ] } } }"
      broken "${text}")
  elseif(CASE STREQUAL "no-normal")
    string(REPLACE "\"NORMAL\": 2, " "" broken "${text}")
  elseif(CASE STREQUAL "short-strip")
    string(REPLACE "\"indices\": 0, \"material\": 0 } ]"
      "\"indices\": 0, \"material\": 0 }, { \"attributes\": { \"POSITION\": 1, \"NORMAL\": 2, \"TEXCOORD_0\": 3 }, \"indices\": 4, \"mode\": 5 } ]"
      broken "${text}")
    string(REPLACE "\"type\": \"VEC2\" }\n"
      "\"type\": \"VEC2\" },\n    { \"bufferView\": 0, \"componentType\": 5123, \"count\": 2, \"type\": \"SCALAR\" }\n"
      broken "${broken}")
  elseif(CASE STREQUAL "bad-indices")
    # The 6 ushort indices read as 3 uints: (1 << 16) | 0 and the like, far out of range.
    string(REPLACE "\"componentType\": 5123, \"count\": 6" "\"componentType\": 5125, \"count\": 3"
      broken "${text}")
  else()
    message(FATAL_ERROR "unknown CASE ${CASE}")
  endif()
  if(broken STREQUAL text)
    message(FATAL_ERROR "CASE ${CASE}: the replacement did not apply to ${SOURCE}")
  endif()
  file(WRITE "${WORK_DIR}/case.gltf" "${broken}")
endif()

string(REPLACE "@WORK@" "${WORK_DIR}" BEFORE "${BEFORE}")
string(REPLACE "|+|" ";" runs "${BEFORE}")
foreach(run IN LISTS runs)
  string(REPLACE "|" ";" run "${run}")
  execute_process(COMMAND "${TOOL}" ${run} WORKING_DIRECTORY "${WORK_DIR}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "a first run failed\ncommand: ${TOOL} ${run}\nexit: ${rc}\n"
      "stdout:\n${out}\nstderr:\n${err}")
  endif()
  message("first run: ${TOOL} ${run}\n${out}")
endforeach()
string(REPLACE "@WORK@" "${WORK_DIR}" ARGS "${ARGS}")
string(REPLACE "|" ";" ARGS "${ARGS}")
string(REPLACE "@WORK@" "${WORK_DIR}" OUT "${OUT}")
execute_process(COMMAND "${TOOL}" ${ARGS} WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(report "command: ${TOOL} ${ARGS}\nexit: ${rc}\nstdout:\n${out}\nstderr:\n${err}")

if(EXPECT STREQUAL "ok")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "expected success\n${report}")
  endif()
  if(OUT AND NOT EXISTS "${OUT}")
    message(FATAL_ERROR "expected ${OUT} to be written\n${report}")
  endif()
  # A .vtp, and each block of a .vtm, keeps its arrays inline: ParaView 5.11's reader cannot
  # read an appended data section with the libexpat1 of Debian bookworm's security updates (see
  # NormalMapFiles.cxx, WriteXML).
  set(pieces)
  if(OUT MATCHES "\\.vtp$")
    set(pieces "${OUT}")
  elseif(OUT MATCHES "\\.vtm$")
    string(REGEX REPLACE "\\.vtm$" "" block_folder "${OUT}")
    file(GLOB pieces "${block_folder}/*.vtp")
    if(NOT pieces)
      message(FATAL_ERROR "${OUT} has no block files in ${block_folder}\n${report}")
    endif()
  endif()
  foreach(piece IN LISTS pieces)
    file(STRINGS "${piece}" appended REGEX "<AppendedData" LIMIT_COUNT 1)
    if(appended)
      message(FATAL_ERROR "${piece} has an appended data section\n${report}")
    endif()
  endforeach()
  if(CHECK)
    string(REPLACE "@WORK@" "${WORK_DIR}" CHECK "${CHECK}")
    string(REPLACE "|" ";" CHECK "${CHECK}")
    execute_process(COMMAND ${CHECK} RESULT_VARIABLE check_rc OUTPUT_VARIABLE check_out
      ERROR_VARIABLE check_out)
    string(APPEND report "check: ${CHECK}\n${check_out}")
    if(NOT check_rc EQUAL 0)
      message(FATAL_ERROR "the check failed\n${report}")
    endif()
    if(CHECK_STDOUT AND NOT check_out MATCHES "${CHECK_STDOUT}")
      message(FATAL_ERROR "the check's output does not match '${CHECK_STDOUT}'\n${report}")
    endif()
  endif()
elseif(EXPECT STREQUAL "fail")
  if(rc EQUAL 0 OR NOT rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "expected a non-zero exit code (not a crash)\n${report}")
  endif()
  string(REGEX REPLACE "\n$" "" trimmed "${err}")
  if(NOT trimmed MATCHES "^normalmap[^\n]*error: [^\n]+$")
    message(FATAL_ERROR "expected one line 'normalmap ...: error: ...' on stderr\n${report}")
  endif()
  if(OUT)
    get_filename_component(out_dir "${OUT}" DIRECTORY)
    get_filename_component(out_name "${OUT}" NAME)
    file(GLOB leftovers "${out_dir}/.${out_name}.tmp-*")
    if(EXISTS "${OUT}" OR leftovers)
      message(FATAL_ERROR "the failed run left ${OUT} ${leftovers}\n${report}")
    endif()
  endif()
  if(EXIT AND NOT rc EQUAL EXIT)
    message(FATAL_ERROR "expected exit code ${EXIT}\n${report}")
  endif()
elseif(EXPECT STREQUAL "defects")
  if(NOT rc EQUAL 1 OR NOT err STREQUAL "")
    message(FATAL_ERROR "expected exit code 1 and nothing on stderr\n${report}")
  endif()
else()
  message(FATAL_ERROR "EXPECT must be ok, fail or defects")
endif()
if(STDOUT AND NOT out MATCHES "${STDOUT}")
  message(FATAL_ERROR "stdout does not match '${STDOUT}'\n${report}")
endif()
if(STDERR AND NOT err MATCHES "${STDERR}")
  message(FATAL_ERROR "stderr does not match '${STDERR}'\n${report}")
endif()
message("${report}")

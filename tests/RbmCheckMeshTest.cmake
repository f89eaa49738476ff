# Command-line test of rbmCheckMesh (registered in apps/CMakeLists.txt):
#   cmake -DRBM_CHECK_MESH=<exe> -DRBM_TEST_DATA_DIR=<tests/data> -P RbmCheckMeshTest.cmake
# Checks exit statuses, that -json prints one parseable JSON object, and a few figures
# against OpenFOAM's checkMesh logs of the same fixtures (tests/data/checkMesh/*/checkMesh*.log).
cmake_minimum_required(VERSION 3.20)

set(fixtures ${RBM_TEST_DATA_DIR}/checkMesh)
function(fail message)
  message(SEND_ERROR "${message}")
endfunction()

# run(<name> <expected exit status> args...): sets ${name}_out, ${name}_err.
function(run name expected)
  execute_process(COMMAND ${RBM_CHECK_MESH} ${ARGN}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL expected)
    fail("rbmCheckMesh ${ARGN}: exit status ${status}, expected ${expected}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  set(${name}_out "${out}" PARENT_SCOPE)
  set(${name}_err "${err}" PARENT_SCOPE)
endfunction()

# expectJson(<json> <expected> keys...): the value at keys equals expected (string compare).
function(expectJson json expected)
  string(JSON value ERROR_VARIABLE error GET "${json}" ${ARGN})
  if(error)
    fail("JSON has no ${ARGN}: ${error}")
  elseif(NOT "${value}" STREQUAL "${expected}")
    fail("JSON ${ARGN} = ${value}, expected ${expected}")
  endif()
endfunction()

# expectJsonDigits(<json> <digits> keys...): the number at keys starts with `digits`
# (CMake has no floating-point arithmetic; checkMesh's logs print 17 significant digits,
# rbm prints the shortest round-trip form, so the first 15 digits must agree).
function(expectJsonDigits json digits)
  string(JSON value ERROR_VARIABLE error GET "${json}" ${ARGN})
  if(error)
    fail("JSON has no ${ARGN}: ${error}")
    return()
  endif()
  string(LENGTH "${digits}" length)
  string(SUBSTRING "${value}" 0 ${length} prefix)
  if(NOT prefix STREQUAL digits)
    fail("JSON ${ARGN} = ${value}, checkMesh printed ${digits}...")
  endif()
endfunction()

# A valid 2D quad mesh: exit 0, 2D metrics, checkMesh's figures.
run(quad 0 -case ${fixtures}/quad2D -json)
string(JSON type ERROR_VARIABLE error TYPE "${quad_out}")
if(error OR NOT type STREQUAL "OBJECT")
  fail("rbmCheckMesh -json did not print a JSON object: ${error}\n${quad_out}")
else()
  expectJson("${quad_out}" 2 dimension)
  expectJson("${quad_out}" "empty" pseudoTwoD)
  expectJson("${quad_out}" 576 mesh cells)
  expectJson("${quad_out}" 576 cellTypes hexahedra)
  expectJson("${quad_out}" ON valid)
  expectJson("${quad_out}" 0 failedChecks)
  expectJson("${quad_out}" 576 thesis quadrilateralShape count)
  # checkMesh: "Mesh non-orthogonality Max: 44.155180739207317 average: 18.956133596871883"
  expectJsonDigits("${quad_out}" "44.1551807392073" checkMesh maxNonOrthogonality)
  expectJsonDigits("${quad_out}" "18.9561335968718" checkMesh averageNonOrthogonality)
  # checkMesh: "Max skewness = 1.00337671302632 OK."
  expectJsonDigits("${quad_out}" "1.00337671302632" checkMesh maxSkewness)
endif()

# The readable report: checkMesh-like lines and the verdict.
run(quadText 0 -case ${fixtures}/quad2D)
foreach(line "Mesh non-orthogonality Max: 44.1552 average: 18.9561" "Max skewness = 1.00338 OK."
             "hexahedra:     576" "Mesh is 2D" "Mesh OK.")
  string(FIND "${quadText_out}" "${line}" at)
  if(at EQUAL -1)
    fail("the report has no line '${line}':\n${quadText_out}")
  endif()
endforeach()

# The moved mesh at time 0.5 folds cells: exit 1; -latestTime picks the same folder.
run(moved 1 -case ${fixtures}/quad2DMoved -time 0.5 -json)
expectJson("${moved_out}" OFF valid)
expectJson("${moved_out}" 2 checkMesh nonPositiveVolumeCells)   # checkMesh: 2 negative volume cells
expectJson("${moved_out}" 10 checkMesh incorrectlyOrientedFaces)   # checkMesh: 10 faces
expectJson("${moved_out}" 3 failedChecks)   # checkMesh: "Failed 3 mesh checks."
expectJson("${moved_out}" 2 invertedCells)
run(latest 1 -case ${fixtures}/quad2DMoved -latestTime -json)
if(NOT latest_out STREQUAL moved_out)
  fail("-latestTime and -time 0.5 differ")
endif()
run(movedText 1 -case ${fixtures}/quad2DMoved -time 0.5)
string(FIND "${movedText_out}" "Failed 3 mesh checks." at)
if(at EQUAL -1)
  fail("the moved mesh's report does not say 'Failed 3 mesh checks.':\n${movedText_out}")
endif()
# -time constant reads the initial mesh: valid.
run(constant 0 -case ${fixtures}/quad2DMoved -time constant -json)

# Bad input: exit 2 with a message naming the problem.
run(missing 2 -case ${fixtures}/noSuchCase)
string(FIND "${missing_err}" "noSuchCase" at)
if(at EQUAL -1)
  fail("no message naming the missing case: ${missing_err}")
endif()
run(noTime 2 -case ${fixtures}/quad2DMoved -time 7)
string(FIND "${noTime_err}" "no time folder 7" at)
if(at EQUAL -1)
  fail("no message about the missing time folder: ${noTime_err}")
endif()
run(badOption 2 -case ${fixtures}/quad2D -frobnicate)
run(both 2 -case ${fixtures}/quad2D -time 0 -latestTime)

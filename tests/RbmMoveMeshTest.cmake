# Command-line test of rbmMoveMesh (registered in apps/CMakeLists.txt):
#   cmake -DRBM_MOVE_MESH=<exe> -DRBM_SOURCE_DIR=<source tree> -DRBM_WORK_DIR=<scratch folder>
#         -P RbmMoveMeshTest.cmake
# Runs the program on a copy of tutorials/naca4415 (4 degrees about the trailing edge in one
# step, writeCompression on) and checks the exit status, the files written, the log line and
# the JSON log; then -help, -version and bad command lines.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/CopyCaseInputs.cmake)

function(fail message)
  message(SEND_ERROR "${message}")
endfunction()

# run(<name> <expected exit status> args...): sets ${name}_out, ${name}_err.
function(run name expected)
  execute_process(COMMAND ${RBM_MOVE_MESH} ${ARGN}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL expected)
    fail("rbmMoveMesh ${ARGN}: exit status ${status}, expected ${expected}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  set(${name}_out "${out}" PARENT_SCOPE)
  set(${name}_err "${err}" PARENT_SCOPE)
endfunction()

function(expectContains text what where)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    fail("${where} does not contain '${what}':\n${text}")
  endif()
endfunction()

# --- The tutorial, in a fresh copy --------------------------------------------------------------
set(case ${RBM_WORK_DIR}/naca4415)
file(REMOVE_RECURSE ${RBM_WORK_DIR})
file(MAKE_DIRECTORY ${RBM_WORK_DIR})
copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415 ${case})

run(tutorial 0 -case ${case})
foreach(file 1/polyMesh/points.gz 1/pointDisplacement.gz VTK/naca4415_0.vtu VTK/naca4415_1.vtu VTK/naca4415.pvd
             postProcessing/rbmMoveMesh/0/log.jsonl)
  if(NOT EXISTS ${case}/${file})
    fail("the run did not write ${file}")
  endif()
endforeach()
# writeCompression on: no uncompressed twin; nothing half-written left behind.
if(EXISTS ${case}/1/polyMesh/points)
  fail("1/polyMesh/points exists next to points.gz")
endif()
file(GLOB_RECURSE leftovers LIST_DIRECTORIES true ${case}/*)
list(FILTER leftovers INCLUDE REGEX "\\.tmp[^/]*$")
if(leftovers)
  fail("temporary files left behind: ${leftovers}")
endif()
# The log line of the one step: time 1, no inverted cell, written.
string(REGEX MATCH "Time = 1 [^\n]*" line "${tutorial_out}")
if(NOT line)
  fail("no log line for time 1:\n${tutorial_out}")
else()
  expectContains("${line}" " inverted 0 " "the log line of time 1")
  expectContains("${line}" "written" "the log line of time 1")
endif()
# The JSON log: one line, a JSON object with 0 inverted cells and a converged solve.
file(STRINGS ${case}/postProcessing/rbmMoveMesh/0/log.jsonl jsonLines)
list(LENGTH jsonLines jsonLineCount)
if(NOT jsonLineCount EQUAL 1)
  fail("log.jsonl has ${jsonLineCount} lines, expected 1 (one per time step)")
else()
  string(JSON inverted ERROR_VARIABLE error GET "${jsonLines}" invertedCells)
  if(error OR NOT inverted EQUAL 0)
    fail("log.jsonl invertedCells = ${inverted} ${error}")
  endif()
  string(JSON converged ERROR_VARIABLE error GET "${jsonLines}" converged)
  if(error OR NOT converged STREQUAL "ON")
    fail("log.jsonl converged = ${converged} ${error}")
  endif()
  string(JSON timeName ERROR_VARIABLE error GET "${jsonLines}" timeName)
  if(error OR NOT timeName STREQUAL "1")
    fail("log.jsonl timeName = ${timeName} ${error}")
  endif()
endif()
# The .pvd lists the initial mesh and time 1.
file(READ ${case}/VTK/naca4415.pvd pvd)
expectContains("${pvd}" "file=\"naca4415_0.vtu\"" "VTK/naca4415.pvd")
expectContains("${pvd}" "file=\"naca4415_1.vtu\"" "VTK/naca4415.pvd")

# --- Options --------------------------------------------------------------------------------------
run(help 0 -help)
expectContains("${help_out}" "Usage: rbmMoveMesh" "-help")
expectContains("${help_out}" "rigidBodyMotionSolverCoeffs" "-help")
expectContains("${help_out}" "writeCompression" "-help")
run(version 0 -version)
expectContains("${version_out}" "rbmMoveMesh " "-version")

# Bad command lines and cases: exit status 2, a message, nothing written.
run(badOption 2 -case ${case} -frobnicate)
expectContains("${badOption_err}" "unknown option '-frobnicate'" "stderr")
expectContains("${badOption_err}" "Usage: rbmMoveMesh" "stderr")
run(stray 2 ${case})
expectContains("${stray_err}" "unexpected argument" "stderr")
run(noCase 2 -case ${RBM_WORK_DIR}/noSuchCase)
expectContains("${noCase_err}" "noSuchCase" "stderr")
if(EXISTS ${RBM_WORK_DIR}/noSuchCase)
  fail("a run on a missing case created it")
endif()
# A PETSc option (underscore) is accepted and passed on.
run(petsc 0 -case ${case} -noVTK -rbm_unused_option 1)

# --- A solve that fails, and a solve too large for the memory (fresh copies) ---------------------
# Newton stopped after one iteration by a PETSc option on the command line: exit status 1,
# PETSc's reason in the message, no time folder for the step.
set(diverging ${RBM_WORK_DIR}/diverging/naca4415)
copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415 ${diverging})
run(diverging 1 -case ${diverging} -noVTK -rbm_reduced_max_it 1)
expectContains("${diverging_err}" "time 1: the motion solver did not converge (DIVERGED_MAX_IT" "stderr")
expectContains("${diverging_err}" "Nothing was written for time 1" "stderr")
if(EXISTS ${diverging}/1)
  fail("a step that did not converge was written: ${diverging}/1")
endif()
# RBM_AVAILABLE_MEMORY_MB below the estimate: exit status 1 before anything is assembled or written.
file(GLOB before RELATIVE ${diverging} ${diverging}/*)
execute_process(COMMAND ${CMAKE_COMMAND} -E env RBM_AVAILABLE_MEMORY_MB=1 ${RBM_MOVE_MESH} -case ${diverging}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE memory_err)
if(NOT status EQUAL 1)
  fail("rbmMoveMesh with RBM_AVAILABLE_MEMORY_MB=1: exit status ${status}, expected 1\n${out}\n${memory_err}")
endif()
expectContains("${memory_err}" "the solve needs about " "stderr")
expectContains("${memory_err}" "but only 1 MiB is available (RBM_AVAILABLE_MEMORY_MB)" "stderr")
expectContains("${memory_err}" "Nothing was written." "stderr")
file(GLOB after RELATIVE ${diverging} ${diverging}/*)
if(NOT before STREQUAL after)
  fail("the run that did not fit in memory changed the case: ${before} -> ${after}")
endif()

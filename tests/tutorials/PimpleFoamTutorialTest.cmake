# Integration test: runs OpenFOAM's pimpleFoam for a few steps on a copy of the inputs of
# tutorials/naca4415PitchingFlow, the mesh moved by rbm's plugin (librbmMotionSolver.so) or, with
# -DMOTION=laplacian, by OpenFOAM's displacementLaplacian (constant/dynamicMeshDict.laplacian).
#   cmake -DRBM_SOURCE_DIR=<source tree> -DRBM_BUILD_DIR=<build tree> -DRBM_WORK_DIR=<scratch>
#         [-DMOTION=rbm|laplacian] [-DSTEPS=10] -DMAX_NON_ORTHOGONALITY=<degrees>
#         -P PimpleFoamTutorialTest.cmake
# Skips (prints "SKIPPED: ...", which tests/CMakeLists.txt declares as the skip message) when
# pimpleFoam is not installed or, for rbm, when the plugin is not built.
# Checks: pimpleFoam exits 0 and prints End after STEPS steps (with rbm, the plugin's line of
# every step says "inverted 0"; the mesh moves: pimpleFoam writes
# polyMesh/points at the times written); forceCoeffs wrote a finite lift coefficient for every
# step; OpenFOAM's checkMesh of every time written says "Mesh OK", no negative-volume cell, max
# non-orthogonality at most MAX_NON_ORTHOGONALITY (the initial mesh: 27.09 degrees).
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/../CopyCaseInputs.cmake)

foreach(required RBM_SOURCE_DIR RBM_BUILD_DIR RBM_WORK_DIR MAX_NON_ORTHOGONALITY)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "PimpleFoamTutorialTest.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT DEFINED MOTION)
  set(MOTION rbm)
endif()
if(NOT DEFINED STEPS)
  set(STEPS 10)
endif()

function(fail message)
  message(SEND_ERROR "${message}")
endfunction()
include(${CMAKE_CURRENT_LIST_DIR}/PluginLogChecks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/TutorialRequirements.cmake)

# --- What is needed, or a visible skip ----------------------------------------------------------
find_program(PIMPLE_FOAM pimpleFoam)
find_program(CHECK_MESH checkMesh)
if(NOT PIMPLE_FOAM OR NOT CHECK_MESH)
  message("SKIPPED: OpenFOAM's pimpleFoam/checkMesh not found (apt-get install openfoam, done by scripts/setup.sh)")
  return()
endif()
set(env WM_PROJECT_DIR=/usr/share/openfoam)
if(DEFINED ENV{WM_PROJECT_DIR})
  set(env WM_PROJECT_DIR=$ENV{WM_PROJECT_DIR})
endif()
if(MOTION STREQUAL "rbm")
  rbm_find_plugin()
  set(libraryPath ${pluginDir})
  if(DEFINED ENV{LD_LIBRARY_PATH})
    string(APPEND libraryPath ":$ENV{LD_LIBRARY_PATH}")
  endif()
  list(APPEND env LD_LIBRARY_PATH=${libraryPath})
  message(STATUS "plugin: ${plugin}")
elseif(NOT MOTION STREQUAL "laplacian")
  message(FATAL_ERROR "MOTION must be rbm or laplacian, not '${MOTION}'")
endif()

# --- A copy of the case's inputs, shortened -----------------------------------------------------
set(case ${RBM_WORK_DIR}/naca4415PitchingFlow)
file(REMOVE_RECURSE ${RBM_WORK_DIR})
copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415PitchingFlow ${case})
if(MOTION STREQUAL "laplacian")
  file(RENAME ${case}/constant/dynamicMeshDict.laplacian ${case}/constant/dynamicMeshDict)
endif()
file(READ ${case}/system/controlDict controlDict)
if(NOT controlDict MATCHES "\ndeltaT +([0-9.eE+-]+);")
  message(FATAL_ERROR "no deltaT in system/controlDict")
endif()
set(deltaT ${CMAKE_MATCH_1})
# endTime = STEPS * deltaT, written as text (CMake's math() knows integers only): deltaT is 0.001.
if(NOT deltaT STREQUAL "0.001")
  message(FATAL_ERROR "the test assumes deltaT 0.001 in system/controlDict, found ${deltaT}")
endif()
math(EXPR halfSteps "${STEPS} / 2")
string(REGEX REPLACE "\nendTime +[^;]*;" "\nendTime ${STEPS}e-3;" controlDict "${controlDict}")
string(REGEX REPLACE "\nwriteInterval +[^;]*;" "\nwriteInterval ${halfSteps};" controlDict "${controlDict}")
file(WRITE ${case}/system/controlDict "${controlDict}")

# --- pimpleFoam ---------------------------------------------------------------------------------
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ${PIMPLE_FOAM} -case ${case}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(WRITE ${RBM_WORK_DIR}/log.pimpleFoam "${out}\n${err}")
if(NOT status EQUAL 0 OR NOT out MATCHES "\nEnd\n")
  fail("pimpleFoam (${MOTION}): exit status ${status}, no End\nstdout (end):\n${out}\nstderr:\n${err}")
  return()
endif()
# pimpleFoam's "Time = t" lines, and no other line starting "Time = " (foamLog-style parsers
# would count a step twice).
string(REGEX MATCHALL "\nTime = [0-9.eE+-]+\n" steps "${out}")
list(LENGTH steps stepCount)
if(NOT stepCount EQUAL STEPS)
  fail("pimpleFoam: ${stepCount} time steps, expected ${STEPS}")
endif()
string(REGEX MATCHALL "\nTime = " timeLines "${out}")
list(LENGTH timeLines timeLineCount)
if(NOT timeLineCount EQUAL STEPS)
  fail("pimpleFoam's log has ${timeLineCount} lines starting 'Time = ' for ${STEPS} steps")
endif()

if(MOTION STREQUAL "rbm")
  checkRbmPluginSteps("${out}" ${STEPS})   # rbm's own line per step, 0 inverted
endif()
file(GLOB lastPoints ${case}/0.0*/polyMesh/points)
if(NOT lastPoints)
  fail("pimpleFoam wrote no polyMesh/points: the mesh did not move")
endif()

# --- Lift history -------------------------------------------------------------------------------
file(GLOB coefficientFiles ${case}/postProcessing/forceCoeffs/0/coefficient*.dat)
if(NOT coefficientFiles)
  fail("forceCoeffs wrote no postProcessing/forceCoeffs/0/coefficient.dat")
else()
  list(GET coefficientFiles 0 coefficientFile)
  file(STRINGS ${coefficientFile} rows REGEX "^[0-9]")
  list(LENGTH rows rowCount)
  if(NOT rowCount EQUAL STEPS)
    fail("${coefficientFile}: ${rowCount} rows, expected ${STEPS}")
  endif()
  foreach(row IN LISTS rows)
    # Time Cd Cs Cl ...: Cl must be a finite number (not nan or inf). The first steps give
    # |Cl| up to about 2000: the flow starts impulsively (pressure impulse ~ U/deltaT).
    string(REGEX REPLACE "[ \t]+" ";" fields "${row}")
    list(GET fields 3 cl)
    if(NOT cl MATCHES "^-?[0-9]\\.[0-9]+e[-+][0-9]+$")
      fail("lift coefficient '${cl}' is not a finite number: ${row}")
    endif()
  endforeach()
  list(GET rows -1 lastRow)
  message(STATUS "forceCoeffs: ${rowCount} rows, last: ${lastRow}")
endif()

# --- checkMesh of the times written -------------------------------------------------------------
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ${CHECK_MESH} -case ${case} -noZero -time 0:
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(WRITE ${RBM_WORK_DIR}/log.checkMesh "${out}\n${err}")
string(REGEX MATCHALL "\nTime = [^\n]*" checkedTimes "${out}")
list(LENGTH checkedTimes checkedCount)
string(REGEX MATCHALL "\nMesh OK\\." okLines "${out}")
list(LENGTH okLines okCount)
if(NOT status EQUAL 0 OR checkedCount LESS 2 OR NOT okCount EQUAL checkedCount)
  fail("checkMesh: exit status ${status}, ${checkedCount} times checked, ${okCount} Mesh OK\n${out}\n${err}")
endif()
checkMeshLogQuality("${out}" ${MAX_NON_ORTHOGONALITY} largest)
message(STATUS "naca4415PitchingFlow (${MOTION}): pimpleFoam ${stepCount} steps, End; checkMesh Mesh OK at "
               "${checkedCount} times, max non-orthogonality ${largest} (bound ${MAX_NON_ORTHOGONALITY})")

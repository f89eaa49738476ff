# Integration test of tutorials/wing3D at its coarse setting: the mesh made by the tutorial's own
# script (meshGeneration/writeBlockMeshDict.py --resolution RESOLUTION), then the pitching wing
# moved by rbm's OpenFOAM plugin inside OpenFOAM v1912's moveDynamicMesh, serial and decomposed
# in two (decomposePar, method simple: the cut crosses the wing and its boundary layer).
#   cmake -DRBM_SOURCE_DIR=<source tree> -DRBM_BUILD_DIR=<build tree> -DRBM_WORK_DIR=<scratch>
#         -DRBM_COMPARE_POINTS=<rbmComparePoints> -DMPIEXEC=<mpiexec> [-DRESOLUTION=0.3]
#         [-DSTEPS=5] [-DDISPLACEMENT_TOLERANCE=<rbm's displacementTolerance>]
#         -DDECOMPOSED_BOUND=<bound> -P Wing3DTutorialTest.cmake
# Skips (prints "SKIPPED: ...", tests/CMakeLists.txt's skip message) without OpenFOAM's programs,
# python3, mpiexec or the plugin.
# Checks, serial and 2 ranks:
#   * moveDynamicMesh exits 0 after STEPS steps; rbm's line of every step says "inverted 0"
#     (the decomposed run's log says it ran distributed over 2 processors);
#   * every point of the wing is where the motion law puts it (checkWingMotion.py: rotation by
#     6 degrees * sin(2 pi t) about the quarter-chord axis, computed there from the law, not from
#     OpenFOAM's field) to 1e-9 chord, at every time, on the whole mesh and on each processor;
#   * checkMesh of the last time finds no negative-volume cell;
#   * every processor point at every time within DECOMPOSED_BOUND of the serial run's, relative
#     to the point's shortest edge (rbmComparePoints --decomposed by pointProcAddressing): the
#     two solves stop within displacementTolerance (1e-6 of the shortest edge) of the same
#     minimum along different paths.
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/../CopyCaseInputs.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/PluginLogChecks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/TutorialRequirements.cmake)

foreach(required RBM_SOURCE_DIR RBM_BUILD_DIR RBM_WORK_DIR RBM_COMPARE_POINTS DECOMPOSED_BOUND)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "Wing3DTutorialTest.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT DEFINED RESOLUTION)
  set(RESOLUTION 0.3)
endif()
if(NOT DEFINED STEPS)
  set(STEPS 5)
endif()

function(fail message)
  message(SEND_ERROR "${message}")
endfunction()

# --- What is needed, or a visible skip ----------------------------------------------------------
rbm_require_openfoam(blockMesh moveDynamicMesh decomposePar checkMesh)
find_program(PYTHON3 python3)
if(NOT PYTHON3)
  message("SKIPPED: python3 not found (the tutorial's mesh script needs it)")
  return()
endif()
if(NOT MPIEXEC)
  message("SKIPPED: no mpiexec (MPI not found by CMake)")
  return()
endif()
rbm_find_plugin()
set(env WM_PROJECT_DIR=/usr/share/openfoam OMP_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1)
if(DEFINED ENV{WM_PROJECT_DIR})
  set(env WM_PROJECT_DIR=$ENV{WM_PROJECT_DIR} OMP_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1)
endif()
set(libraryPath ${pluginDir})
if(DEFINED ENV{LD_LIBRARY_PATH})
  string(APPEND libraryPath ":$ENV{LD_LIBRARY_PATH}")
endif()
list(APPEND env LD_LIBRARY_PATH=${libraryPath})
set(tutorial ${RBM_SOURCE_DIR}/tutorials/wing3D)

# --- The mesh, and the case shortened to STEPS steps of 0.05 ------------------------------------
file(REMOVE_RECURSE ${RBM_WORK_DIR})
set(mesh ${RBM_WORK_DIR}/mesh)
copyCaseInputs(${tutorial} ${mesh})
execute_process(COMMAND ${PYTHON3} ${tutorial}/meshGeneration/writeBlockMeshDict.py
                        --resolution ${RESOLUTION} --output ${mesh}/system/blockMeshDict
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} blockMesh -case ${mesh}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "blockMesh failed (${status}):\n${out}\n${err}")
endif()
if(DEFINED DISPLACEMENT_TOLERANCE)
  # Both runs stop closer to the minimum, so that they can be compared more tightly. The
  # relative gradient test goes too: it stops at 1e-10 of the first gradient, which depends on
  # the start (the serial run's harmonic warm start begins far closer to the minimum than a
  # part's), and with it the decomposed run's first step stopped 5.4e-6 of an edge away.
  file(READ ${mesh}/constant/dynamicMeshDict dynamicMeshDict)
  string(REPLACE "rigidBodyMotionSolverCoeffs\n{"
         "rigidBodyMotionSolverCoeffs\n{\n    displacementTolerance ${DISPLACEMENT_TOLERANCE};\n    relativeTolerance 1e-14;"
         dynamicMeshDict "${dynamicMeshDict}")
  if(NOT dynamicMeshDict MATCHES "displacementTolerance ${DISPLACEMENT_TOLERANCE};")
    message(FATAL_ERROR "no rigidBodyMotionSolverCoeffs block in the tutorial's constant/dynamicMeshDict")
  endif()
  file(WRITE ${mesh}/constant/dynamicMeshDict "${dynamicMeshDict}")
endif()
file(READ ${mesh}/system/controlDict controlDict)
if(NOT controlDict MATCHES "\ndeltaT +0.05;")
  message(FATAL_ERROR "the test assumes deltaT 0.05 in the tutorial's system/controlDict")
endif()
math(EXPR endTimeHundredths "${STEPS} * 5")
if(endTimeHundredths LESS 10)
  set(endTime "0.0${endTimeHundredths}")
else()
  set(endTime "0.${endTimeHundredths}")
endif()
string(REGEX REPLACE "\nendTime +[^;]*;" "\nendTime ${endTime};" controlDict "${controlDict}")
file(WRITE ${mesh}/system/controlDict "${controlDict}")
set(times)
foreach(step RANGE 1 ${STEPS})
  math(EXPR hundredths "${step} * 5")
  if(hundredths LESS 10)
    list(APPEND times "0.0${hundredths}")
  elseif(hundredths MATCHES "0$")
    string(REGEX REPLACE "0$" "" tenths "${hundredths}")
    list(APPEND times "0.${tenths}")
  else()
    list(APPEND times "0.${hundredths}")
  endif()
endforeach()

function(runCase case command logName)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ${command}
                  WORKING_DIRECTORY ${case} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(WRITE ${case}/${logName} "${out}\n${err}")
  if(NOT status EQUAL 0 OR NOT out MATCHES "\nEnd\n")
    message(FATAL_ERROR "${command} in ${case}: exit status ${status}, no End\n${out}\n${err}")
  endif()
  set(runOutput "${out}" PARENT_SCOPE)
endfunction()

function(checkWing caseOrProcessor)
  execute_process(COMMAND ${PYTHON3} ${tutorial}/checkWingMotion.py ${caseOrProcessor} 1e-9
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}${err}")
  if(NOT status EQUAL 0 OR NOT out MATCHES "over [1-9][0-9]* points and ${STEPS} times")
    fail("the wing's points of ${caseOrProcessor} are not where the motion law puts them:\n${out}${err}")
  endif()
endfunction()

function(checkNoNegativeVolume case)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} checkMesh -case ${case} -latestTime
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT out MATCHES "non-orthogonality Max")
    fail("checkMesh -latestTime of ${case} did not run:\n${out}\n${err}")
  elseif(out MATCHES "negative volume|ncorrectly oriented")
    fail("checkMesh -latestTime of ${case} finds inverted cells:\n${out}")
  endif()
endfunction()

# --- Serial ---------------------------------------------------------------------------------------
set(serial ${RBM_WORK_DIR}/serial)
copyCaseInputs(${mesh} ${serial})
runCase(${serial} moveDynamicMesh log.moveDynamicMesh)
checkRbmPluginSteps("${runOutput}" ${STEPS})
checkWing(${serial})
checkNoNegativeVolume(${serial})

# --- Decomposed in two, the plugin solving on each processor's part ------------------------------
set(decomposed ${RBM_WORK_DIR}/decomposed)
copyCaseInputs(${mesh} ${decomposed})
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} decomposePar -case ${decomposed}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "decomposePar failed (${status}):\n${out}\n${err}")
endif()
runCase(${decomposed} "${MPIEXEC};--allow-run-as-root;--oversubscribe;-n;2;-x;LD_LIBRARY_PATH;-x;WM_PROJECT_DIR;-x;OMP_NUM_THREADS;moveDynamicMesh;-parallel" log.moveDynamicMesh)
if(NOT runOutput MATCHES "distributed over 2 processors")
  fail("the decomposed run did not solve on the processors' parts (no 'distributed over 2 processors' in its log)")
endif()
checkRbmPluginSteps("${runOutput}" ${STEPS})
foreach(processor 0 1)
  checkWing(${decomposed}/processor${processor})
endforeach()
foreach(time IN LISTS times)
  execute_process(COMMAND ${RBM_COMPARE_POINTS} --decomposed ${serial}/constant/polyMesh
                          ${serial}/${time}/polyMesh/points ${decomposed} ${time} ${DECOMPOSED_BOUND}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "t = ${time}: decomposed against serial: ${out}${err}")
  if(NOT status EQUAL 0)
    fail("t = ${time}: the decomposed run is not within ${DECOMPOSED_BOUND} of each point's shortest edge of the serial run: ${out}${err}")
  endif()
endforeach()

# Integration test of the OpenFOAM 13 flow tutorial: tutorials/naca4415PitchingFlowOpenFOAM13's
# own Allrun (foamRun -solver incompressibleFluid, then checkMesh of the times written) for a
# few steps on a copy of its inputs, the mesh moved by rbm's librbmMotionSolverOF13.so or, with
# -DMOTION=laplacian, by OpenFOAM 13's displacementLaplacian.
#   cmake -DRBM_SOURCE_DIR=<source tree> -DRBM_PLUGIN=<librbmMotionSolverOF13.so or empty>
#         -DOPENFOAM13_DIR=<WM_PROJECT_DIR> -DRBM_WORK_DIR=<scratch> [-DMOTION=rbm|laplacian]
#         [-DSTEPS=10] -DMAX_NON_ORTHOGONALITY=<degrees> -P FoamRunTutorialTest.cmake
# Skips ("skipped: OpenFOAM 13 not installed ...") without the OpenFOAM 13 plugin.
# Checks: Allrun exits 0, foamRun prints End after STEPS steps (with rbm, the plugin's line of
# every step says "inverted 0"); forceCoeffs wrote a finite lift coefficient for every step;
# checkMesh of every time written says "Mesh OK", no negative-volume cell, max
# non-orthogonality at most MAX_NON_ORTHOGONALITY (the initial mesh: 27.09 degrees).
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/../CopyCaseInputs.cmake)

foreach(required RBM_SOURCE_DIR OPENFOAM13_DIR RBM_WORK_DIR MAX_NON_ORTHOGONALITY)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "FoamRunTutorialTest.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT DEFINED MOTION)
  set(MOTION rbm)
endif()
if(NOT DEFINED STEPS)
  set(STEPS 10)
endif()
if(NOT RBM_PLUGIN)
  message("skipped: OpenFOAM 13 not installed (librbmMotionSolverOF13.so was not built: "
          "scripts/unpackOpenFOAM13.sh found no OpenFOAM 13 tarball; docs/openfoam13.md)")
  return()
endif()

function(fail message)
  message(FATAL_ERROR "${message}")
endfunction()
include(${CMAKE_CURRENT_LIST_DIR}/PluginLogChecks.cmake)

# --- A copy of the case's inputs and Allrun, shortened ----------------------------------------
set(tutorial ${RBM_SOURCE_DIR}/tutorials/naca4415PitchingFlowOpenFOAM13)
set(case ${RBM_WORK_DIR}/naca4415PitchingFlowOpenFOAM13)
file(REMOVE_RECURSE ${RBM_WORK_DIR})
copyCaseInputs(${tutorial} ${case})
file(COPY ${tutorial}/Allrun DESTINATION ${case})
file(READ ${case}/system/controlDict controlDict)
if(NOT controlDict MATCHES "\ndeltaT +0.001;")
  fail("the test assumes deltaT 0.001 in ${tutorial}/system/controlDict")
endif()
math(EXPR halfSteps "${STEPS} / 2")
string(REGEX REPLACE "\nendTime +[^;]*;" "\nendTime ${STEPS}e-3;" controlDict "${controlDict}")
string(REGEX REPLACE "\nwriteInterval +[^;]*;" "\nwriteInterval ${halfSteps};" controlDict "${controlDict}")
file(WRITE ${case}/system/controlDict "${controlDict}")

get_filename_component(pluginDir ${RBM_PLUGIN} DIRECTORY)
set(arguments "")
set(runFolder ${case})
if(MOTION STREQUAL "laplacian")
  set(arguments -motion laplacian)
  set(runFolder ${case}/laplacian)
elseif(NOT MOTION STREQUAL "rbm")
  fail("MOTION must be rbm or laplacian, not '${MOTION}'")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env RBM_OPENFOAM13_DIR=${OPENFOAM13_DIR} RBM_PLUGIN_DIR=${pluginDir}
                        ${case}/Allrun ${arguments}
                RESULT_VARIABLE status OUTPUT_VARIABLE allrun ERROR_VARIABLE allrun)
if(NOT status EQUAL 0)
  fail("Allrun ${arguments}: exit status ${status}:\n${allrun}")
endif()

# --- foamRun ----------------------------------------------------------------------------------
file(READ ${runFolder}/log.foamRun out)
if(NOT out MATCHES "\nEnd\n")
  fail("foamRun (${MOTION}): no End\n${out}")
endif()
string(REGEX MATCHALL "\nTime = [0-9.eE+-]+s\n" steps "${out}")
list(LENGTH steps stepCount)
if(NOT stepCount EQUAL STEPS)
  fail("foamRun: ${stepCount} time steps, expected ${STEPS}")
endif()
if(MOTION STREQUAL "rbm")
  checkRbmPluginSteps("${out}" ${STEPS})
endif()

# --- Lift history: Time Cm Cd Cl ... -----------------------------------------------------------
set(coefficientFile ${runFolder}/postProcessing/forceCoeffs/0/forceCoeffs.dat)
if(NOT EXISTS ${coefficientFile})
  fail("forceCoeffs wrote no ${coefficientFile}")
endif()
# OpenFOAM 13's forceCoeffs also writes a row at the start time (t = 0): the steps' rows after it.
file(STRINGS ${coefficientFile} rows REGEX "^[0-9]")
list(FILTER rows EXCLUDE REGEX "^0[ \t]")
list(LENGTH rows rowCount)
if(NOT rowCount EQUAL STEPS)
  fail("${coefficientFile}: ${rowCount} rows, expected ${STEPS}")
endif()
foreach(row IN LISTS rows)
  string(REGEX REPLACE "[ \t]+" ";" fields "${row}")
  list(GET fields 3 cl)
  if(NOT cl MATCHES "^-?[0-9]\\.[0-9]+e[-+][0-9]+$")
    fail("lift coefficient '${cl}' is not a finite number: ${row}")
  endif()
endforeach()

# --- checkMesh of the times written ------------------------------------------------------------
file(READ ${runFolder}/log.checkMesh out)
string(REGEX MATCHALL "\nTime = [^\n]*" checkedTimes "${out}")
list(LENGTH checkedTimes checkedCount)
string(REGEX MATCHALL "\nMesh OK\\." okLines "${out}")
list(LENGTH okLines okCount)
if(checkedCount LESS 2 OR NOT okCount EQUAL checkedCount)
  fail("checkMesh: ${checkedCount} times checked, ${okCount} Mesh OK\n${out}")
endif()
checkMeshLogQuality("${out}" ${MAX_NON_ORTHOGONALITY} largest)
message(STATUS "naca4415PitchingFlowOpenFOAM13 (${MOTION}): foamRun ${stepCount} steps, End; checkMesh Mesh OK at "
               "${checkedCount} times, max non-orthogonality ${largest} (bound ${MAX_NON_ORTHOGONALITY})")

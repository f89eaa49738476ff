# Integration test of tutorials/wingMotion2D6DoF (the flow drives a spring-mounted wing through
# OpenFOAM's sixDoFRigidBodyDisplacement condition; rbm's plugin moves the mesh), shortened:
# the tutorial's own scripts on a copy of its inputs, with simpleFoam's steady start cut to
# SIMPLE_ITERATIONS iterations and both pimpleFoam runs stopped at END_TIME:
#   meshGeneration/Allmesh, then Allrun -endTime END_TIME (rbm) and Allrun -openfoam -endTime
#   END_TIME (OpenFOAM's own sixDoFRigidBodyMotion solver: the reference).
#   cmake -DRBM_SOURCE_DIR=<source tree> -DRBM_BUILD_DIR=<build tree> -DRBM_WORK_DIR=<scratch>
#         -DEND_TIME=<s> -DSIMPLE_ITERATIONS=<n> -DMIN_ROTATION=<degrees>
#         -DMAX_NON_ORTHOGONALITY=<degrees> -DFORCE_TOLERANCE=<relative>
#         -P WingMotion6DoFTutorialTest.cmake
# Skips (prints "SKIPPED: ...", the skip message tests/CMakeLists.txt declares) without
# OpenFOAM's programs or without the plugin.
# Checks, with rbm: pimpleFoam exits 0 and prints End; the plugin's line of every step says
# "inverted 0"; the body turned by more than MIN_ROTATION degrees (its "Orientation" in the log,
# first step to last); checkMesh at t = 0 and END_TIME: no negative-volume cell, no more failed
# checks than the initial mesh's one (a face of skewness 4.77 left by snappyHexMesh: "Mesh OK"
# is not reachable on this mesh), max non-orthogonality at most MAX_NON_ORTHOGONALITY (initial
# 49.82 degrees); every row of the wing's forces (postProcessing/forces/0/force.dat) finite, and
# the y force and z moment at every step within FORCE_TOLERANCE (relative to the largest
# |value| of OpenFOAM's run) of OpenFOAM's own run at the same step (same time to 1e-3 relative).
cmake_minimum_required(VERSION 3.20)

foreach(required RBM_SOURCE_DIR RBM_BUILD_DIR RBM_WORK_DIR END_TIME SIMPLE_ITERATIONS MIN_ROTATION
                 MAX_NON_ORTHOGONALITY FORCE_TOLERANCE)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "WingMotion6DoFTutorialTest.cmake: -D${required}=... is required")
  endif()
endforeach()

function(fail message)
  message(SEND_ERROR "${message}")
endfunction()
include(${CMAKE_CURRENT_LIST_DIR}/PluginLogChecks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/TutorialRequirements.cmake)

# --- What is needed, or a visible skip ----------------------------------------------------------
rbm_require_openfoam(pimpleFoam simpleFoam checkMesh blockMesh snappyHexMesh extrudeMesh createPatch mapFields)
rbm_find_plugin()
message(STATUS "plugin: ${plugin}")
set(env RBM_PLUGIN_DIR=${pluginDir} OMP_NUM_THREADS=1)
if(DEFINED ENV{WM_PROJECT_DIR})
  list(APPEND env WM_PROJECT_DIR=$ENV{WM_PROJECT_DIR})
else()
  list(APPEND env WM_PROJECT_DIR=/usr/share/openfoam)
endif()

# --- A copy of the tutorial's inputs and scripts, shortened -------------------------------------
set(tutorial ${RBM_SOURCE_DIR}/tutorials/wingMotion2D6DoF)
set(case ${RBM_WORK_DIR}/wingMotion2D6DoF)
file(REMOVE_RECURSE ${RBM_WORK_DIR})
file(MAKE_DIRECTORY ${case})
foreach(part 0.orig constant system meshGeneration Allrun Allclean)
  file(COPY ${tutorial}/${part} DESTINATION ${case})
endforeach()
execute_process(COMMAND ${case}/Allclean)   # what a run in the tutorial folder left in meshGeneration
set(steadyControl ${case}/meshGeneration/wingMotion2D_simpleFoam/system/controlDict)
file(READ ${steadyControl} text)
string(REGEX REPLACE "\nendTime +[^;]*;" "\nendTime ${SIMPLE_ITERATIONS};" text "${text}")
string(REGEX REPLACE "\nwriteInterval +[^;]*;" "\nwriteInterval ${SIMPLE_ITERATIONS};" text "${text}")
file(WRITE ${steadyControl} "${text}")
# Write END_TIME (and 0): checkMesh checks both.
file(READ ${case}/system/controlDict text)
string(REGEX REPLACE "\nwriteInterval +[^;]*;" "\nwriteInterval ${END_TIME};" text "${text}")
file(WRITE ${case}/system/controlDict "${text}")

function(run name)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ${ARGN}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(WRITE ${RBM_WORK_DIR}/log.${name} "${out}\n${err}")
  set(status ${status} PARENT_SCOPE)
  set(out "${out}\n${err}" PARENT_SCOPE)
endfunction()

run(Allmesh ${case}/meshGeneration/Allmesh)
if(NOT status EQUAL 0)
  fail("meshGeneration/Allmesh: exit status ${status}\n${out}")
  return()
endif()
run(Allrun ${case}/Allrun -endTime ${END_TIME})
if(NOT status EQUAL 0)
  fail("Allrun (rbm): exit status ${status}\n${out}")
endif()
run(AllrunOpenFOAM ${case}/Allrun -openfoam -endTime ${END_TIME})
if(NOT status EQUAL 0)
  fail("Allrun -openfoam: exit status ${status}\n${out}")
endif()

# --- pimpleFoam's log ---------------------------------------------------------------------------
foreach(motion rbm openfoam)
  if(motion STREQUAL "rbm")
    set(folder ${case})
  else()
    set(folder ${case}/openfoam)
  endif()
  set(log ${folder}/log.pimpleFoam)
  if(NOT EXISTS ${log})
    fail("${motion}: no ${log}")
    continue()
  endif()
  file(READ ${log} text)
  if(NOT text MATCHES "\nEnd\n")
    fail("${motion}: pimpleFoam did not end (no End in ${log})")
  endif()
  string(REGEX MATCHALL "\nTime = [0-9.eE+-]+\n" steps "${text}")
  list(LENGTH steps stepCount_${motion})
  if(motion STREQUAL "rbm")
    checkRbmPluginSteps("${text}" ${stepCount_rbm})
  endif()
  # The body's rotation, first step to last: sin(theta1 - theta0) = yx1 xx0 - xx1 yx0 for unit
  # (xx, yx) (the 2D rotation part of the orientation), in micro-units to stay in integers.
  file(STRINGS ${log} orientations REGEX "^    Orientation: ")
  list(LENGTH orientations orientationCount)
  if(orientationCount LESS 2)
    fail("${motion}: fewer than 2 'Orientation:' lines in ${log} (report on?)")
    set(rotation_${motion} 0)
  else()
    list(GET orientations 0 first)
    list(GET orientations -1 last)
    foreach(which first last)
      string(REGEX REPLACE ".*\\(([^)]*)\\).*" "\\1" numbers "${${which}}")
      string(REGEX REPLACE " +" ";" numbers "${numbers}")
      list(GET numbers 0 xx_${which})
      list(GET numbers 3 yx_${which})
    endforeach()
    set(rotation_${motion} "${yx_last}*${xx_first} - ${xx_last}*${yx_first}")
  endif()
  # checkMesh (Allrun ran it at every time written: 0 and END_TIME).
  file(READ ${folder}/log.checkMesh checkText)
  string(REGEX MATCHALL "\nTime = [^\n]*" checkedTimes "${checkText}")
  list(LENGTH checkedTimes checkedCount_${motion})
  if(checkedCount_${motion} LESS 2)
    fail("${motion}: checkMesh checked ${checkedCount_${motion}} times, expected 0 and ${END_TIME}")
  endif()
  if(checkText MATCHES "negative volume")
    fail("${motion}: checkMesh found negative-volume (inverted) cells")
  endif()
  string(REGEX MATCHALL "Failed [0-9]+ mesh checks" failedChecks "${checkText}")
  foreach(entry IN LISTS failedChecks)
    string(REGEX REPLACE "Failed ([0-9]+) .*" "\\1" count "${entry}")
    if(count GREATER 1)
      fail("${motion}: checkMesh: ${entry} (the initial mesh fails 1)")
    endif()
  endforeach()
  string(REGEX MATCHALL "non-orthogonality Max: [0-9.]+" nonOrthogonality "${checkText}")
  set(largest_${motion} 0)
  foreach(entry IN LISTS nonOrthogonality)
    string(REGEX REPLACE ".*: " "" value "${entry}")
    if(motion STREQUAL "rbm" AND value GREATER MAX_NON_ORTHOGONALITY)
      fail("rbm: max non-orthogonality ${value} > ${MAX_NON_ORTHOGONALITY} degrees")
    endif()
    if(value GREATER largest_${motion})
      set(largest_${motion} ${value})
    endif()
  endforeach()
  # Forces: "t (total) (pressure) (viscous)" per step.
  set(forceFile ${folder}/postProcessing/forces/0/force.dat)
  set(momentFile ${folder}/postProcessing/forces/0/moment.dat)
  if(NOT EXISTS ${forceFile} OR NOT EXISTS ${momentFile})
    fail("${motion}: no ${forceFile} or ${momentFile}")
    set(forces_${motion} "")
    set(moments_${motion} "")
  else()
    file(STRINGS ${forceFile} forces_${motion} REGEX "^[0-9]")
    file(STRINGS ${momentFile} moments_${motion} REGEX "^[0-9]")
  endif()
endforeach()

# --- Numbers: CMake's math() knows integers only; one python3 or awk call does the arithmetic ----
find_program(AWK awk)
if(NOT AWK)
  message("SKIPPED: awk not found")
  return()
endif()
foreach(motion rbm openfoam)
  string(REPLACE ";" "\n" text "${forces_${motion}}")
  file(WRITE ${RBM_WORK_DIR}/force.${motion} "${text}\n")
  string(REPLACE ";" "\n" text "${moments_${motion}}")
  file(WRITE ${RBM_WORK_DIR}/moment.${motion} "${text}\n")
endforeach()
file(WRITE ${RBM_WORK_DIR}/compare.awk [=[
# force.rbm moment.rbm force.openfoam moment.openfoam: rows "t\t(fx fy fz)\t(...)\t(...)"
{ gsub(/[()]/, "") }
FILENAME ~ /force.rbm$/      { if (NF < 4) next; fr[++nfr] = $3; tr[nfr] = $1; if (!finite($2) || !finite($3) || !finite($4)) bad++ }
FILENAME ~ /moment.rbm$/     { if (NF < 4) next; mr[++nmr] = $4; if (!finite($4)) bad++ }
FILENAME ~ /force.openfoam$/ { if (NF < 4) next; fo[++nfo] = $3; to[nfo] = $1 }
FILENAME ~ /moment.openfoam$/{ if (NF < 4) next; mo[++nmo] = $4 }
function finite(x) { return x ~ /^-?[0-9]/ && x+0 == x+0 && x+0 < 1e30 && x+0 > -1e30 }
function abs(x) { return x < 0 ? -x : x }
END {
  n = nfr < nfo ? nfr : nfo
  for (i = 1; i <= nfo; i++) { if (abs(fo[i]) > fmax) fmax = abs(fo[i]); if (abs(mo[i]) > mmax) mmax = abs(mo[i]) }
  for (i = 1; i <= n; i++) {
    if (abs(tr[i] - to[i]) > 1e-3 * abs(to[i])) { timeMismatch = i; break }
    df = abs(fr[i] - fo[i]) / fmax; dm = abs(mr[i] - mo[i]) / mmax
    if (df > worstF) { worstF = df; tf = tr[i] }
    if (dm > worstM) { worstM = dm; tm = tr[i] }
  }
  printf "rows %d %d %d bad %d timeMismatch %d worstFy %.3g %g worstMz %.3g %g maxFy %.6g maxMz %.6g lastFy %s %s lastMz %s %s\n",
         nfr, nfo, n, bad, timeMismatch, worstF, tf+0, worstM, tm+0, fmax, mmax, fr[nfr], fo[nfo], mr[nmr], mo[nmo]
}
]=])
execute_process(COMMAND ${AWK} -f ${RBM_WORK_DIR}/compare.awk
                        ${RBM_WORK_DIR}/force.rbm ${RBM_WORK_DIR}/moment.rbm
                        ${RBM_WORK_DIR}/force.openfoam ${RBM_WORK_DIR}/moment.openfoam
                OUTPUT_VARIABLE comparison OUTPUT_STRIP_TRAILING_WHITESPACE)
message(STATUS "forces, rbm against OpenFOAM's run: ${comparison}")
separate_arguments(fields UNIX_COMMAND "${comparison}")
list(GET fields 1 rowsRbm)
list(GET fields 2 rowsOpenFOAM)
list(GET fields 3 rowsCompared)
list(GET fields 5 badRows)
list(GET fields 7 timeMismatch)
list(GET fields 9 worstFy)
list(GET fields 12 worstMz)
if(NOT rowsRbm EQUAL stepCount_rbm OR rowsRbm LESS 5)
  fail("rbm: ${rowsRbm} rows of forces for ${stepCount_rbm} steps")
endif()
if(NOT badRows EQUAL 0)
  fail("rbm: ${badRows} force/moment values not finite")
endif()
if(NOT timeMismatch EQUAL 0)
  fail("rbm and OpenFOAM's runs reach different times at step ${timeMismatch}")
endif()
execute_process(COMMAND ${AWK} "BEGIN{exit !(${worstFy} <= ${FORCE_TOLERANCE} && ${worstMz} <= ${FORCE_TOLERANCE})}"
                RESULT_VARIABLE withinTolerance)
if(NOT withinTolerance EQUAL 0)
  fail("forces: rbm differs from OpenFOAM's run by ${worstFy} (Fy) and ${worstMz} (Mz) of the largest, tolerance ${FORCE_TOLERANCE}")
endif()
# Rotation in degrees: asin of the cross product.
foreach(motion rbm openfoam)
  execute_process(COMMAND ${AWK} "BEGIN{s = ${rotation_${motion}}; printf \"%.6f\", atan2(s, sqrt(1 - s*s)) * 45 / atan2(1, 1)}"
                  OUTPUT_VARIABLE degrees_${motion})
endforeach()
execute_process(COMMAND ${AWK} "BEGIN{r = ${degrees_rbm}; exit !(r > ${MIN_ROTATION} || -r > ${MIN_ROTATION})}"
                RESULT_VARIABLE turned)
if(NOT turned EQUAL 0)
  fail("rbm: the wing turned ${degrees_rbm} degrees, expected more than ${MIN_ROTATION} in magnitude")
endif()
message(STATUS "wingMotion2D6DoF: rbm ${stepCount_rbm} steps, OpenFOAM ${stepCount_openfoam} steps, End; "
               "rotation rbm ${degrees_rbm} degrees, OpenFOAM ${degrees_openfoam}; checkMesh at "
               "${checkedCount_rbm} times, no negative volume, max non-orthogonality rbm ${largest_rbm} "
               "(bound ${MAX_NON_ORTHOGONALITY}), OpenFOAM ${largest_openfoam}")

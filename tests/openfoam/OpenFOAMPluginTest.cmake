# Tests of the OpenFOAM plugin (registered in tests/CMakeLists.txt), on either OpenFOAM:
#   cmake -DMODE=<mode> -DOPENFOAM=<1912 or 13> -DRBM_PLUGIN=<the plugin's .so or empty>
#         -DRBM_MOVE_MESH=<exe> -DRBM_COMPARE_POINTS=<exe> -DRBM_SOURCE_DIR=<source tree>
#         -DRBM_WORK_DIR=<scratch> [-DOPENFOAM13_DIR=<WM_PROJECT_DIR>] -P OpenFOAMPluginTest.cmake
# OPENFOAM=1912: librbmMotionSolver.so in Debian's OpenFOAM v1912 (moveDynamicMesh, pimpleFoam).
# OPENFOAM=13: librbmMotionSolverOF13.so in OpenFOAM 13 (foamRun -solver movingMesh, foamRun
# -solver incompressibleFluid; every OpenFOAM program run with OPENFOAM13_DIR/etc/bashrc sourced).
# The cases are written for v1912; for OpenFOAM 13 prepareCase translates them (the mover
# dictionary, a PIMPLE block for movingMesh, physicalProperties and momentumTransport), and the
# unit OpenFOAM 13 gives times in its log ("Time = 0.005s") is dropped, so the checks are the same.
# The expectation is always rbmMoveMesh's own output on the same case and options (an
# independent front door over the same core: its boundary conditions are rbm's, the plugin's
# are OpenFOAM's), or OpenFOAM's own behaviour:
#   serial2D        naca4415 (4° about the trailing edge, pseudo-2D) with moveDynamicMesh: the
#                   points equal rbmMoveMesh's to 1e-8 chord, the log line's figures too; one
#                   line of the log starts with "Time = " (rbm's own starts with its name).
#   oneLineSwitch   naca4415 switched with the two lines only (no rigidBodyMotionSolverCoeffs,
#                   the previous solver's entries left in dynamicMeshDict): equals rbmMoveMesh
#                   with the defaults to 1e-8; a misspelt entry in the block is a FATAL IO ERROR
#                   naming it.
#   interfacePatches the channel in two blocks joined by cyclicAMI patches: a FatalError naming
#                   the patch and its type, nothing written. OpenFOAM 13 (no cyclicAMI): the blocks
#                   joined by a plain cyclic pair, which rbm supports: the run completes and the
#                   pair's points move together to 1e-12.
#   cyclicSector    a 60° annulus sector whose sides are a rotational cyclic pair, its inner arc
#                   turning: moveDynamicMesh equals rbmMoveMesh to 1e-8, pairs u_B = R u_A to 1e-12.
#   cyclicChannel   the oscillatingChannel with its sides a translational cyclic pair: 5 steps of
#                   pimpleFoam equal rbmMoveMesh's to 1e-8 with the pairs together to 1e-12; the
#                   same decomposed in two across the channel (each pair on one processor),
#                   `mpirun -np 2 pimpleFoam -parallel`: equal to the serial run to 1e-8, pairs
#                   to 1e-12. v1912 also: decomposed along the channel (processorCyclic
#                   patches) a FatalError naming the remedy; with preservePatches equal to the
#                   serial run to 1e-8.
#   serial3D        tutorials/cube (3D, 30 linearized sub-steps) with moveDynamicMesh: the points
#                   equal rbmMoveMesh's to 1e-9 (cells are about 0.1 wide).
#   flowSteps       tests/data/openfoamPlugin/oscillatingChannel: 5 steps of pimpleFoam (slip
#                   sides, oscillatingDisplacement bottom, mesh fluxes); the points equal
#                   rbmMoveMesh's to 1e-8.
#   restart         naca4415Pitching shortened to 6 steps: moveDynamicMesh equals rbmMoveMesh at
#                   every written time; a run stopped after 3 steps and restarted from its last
#                   written time (startFrom latestTime) ends at the same mesh to 1e-8.
#   badCoefficient  `coupling bogus;` stops moveDynamicMesh with OpenFOAM's FOAM FATAL IO ERROR
#                   naming the dictionary and the entry; `writeInvalid maybe;` too.
#   invertedCells   a rotation that inverts cells stops the run with a FatalError giving the
#                   count; with `writeInvalid yes;` the run goes on and warns.
#   parallel        the oscillatingChannel decomposed in two (decomposePar), 5 steps of
#                   `mpirun -np 2 pimpleFoam -parallel`, reconstructPar: the points equal the
#                   serial rbmMoveMesh's to 1e-8 (MPIEXEC: the mpiexec to use).
#   decomposed3D    tests/data/decomposedTwist/np2 (a column whose lid turns 20° in two steps, its
#                   sides sliding; decomposePar's processor folders, method manual, the lid's
#                   edge on the cut): `mpirun -np 2 moveDynamicMesh -parallel` solves on the
#                   processors' parts (the log says "distributed over 2 processors"; no rank
#                   gathers the mesh): at both times every point of every processor folder
#                   (by pointProcAddressing: the fixture keeps no other addressing for
#                   reconstructPar) within 2.5e-6 of its shortest edge of rbmMoveMesh's serial
#                   run (each solve stops within displacementTolerance 1e-6 of the minimum,
#                   along a different path), the
#                   quality figures of the step lines equal; the same case with
#                   RBM_PLUGIN_GATHER=1 takes the gathered path (its log says so and why) and
#                   ends within the same bound; `tolerance bogus;` stops both ranks with a FOAM
#                   FATAL IO ERROR naming it, nothing written.
#   aliasName       naca4415 with OpenFOAM's own librigidBodyMeshMotion.so loaded too (it
#                   registers rigidBodyMotionSolver as well) and rbm selected as rbmMotionSolver
#                   with an rbmMotionSolverCoeffs block (subSteps 2): equals rbmMoveMesh with
#                   subSteps 2 to 1e-8, the log line's figures too.
# Without the plugin the test prints "skipped: OpenFOAM not installed" (CTest: skipped).
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/../CopyCaseInputs.cmake)

if(OPENFOAM STREQUAL "13")
  if(NOT RBM_PLUGIN)
    message("skipped: OpenFOAM 13 not installed (the plugin librbmMotionSolverOF13.so was not "
            "built: scripts/unpackOpenFOAM13.sh found no OpenFOAM 13 tarball to unpack into "
            "third_party/; docs/openfoam13.md)")
    return()
  endif()
  # OpenFOAM 13's programs need its environment (PATH, LD_LIBRARY_PATH with its MPI's Pstream):
  # bash sources etc/bashrc, without arguments (it reads its own as settings), and runs the
  # command. Lines, not semicolons, which would split the CMake list.
  set(openfoamEnvironment bash -c "command=(\"\$@\")\nset --\nset +u\nsource '${OPENFOAM13_DIR}/etc/bashrc'\nexec \"\${command[@]}\"" openfoam13)
  set(moveMesh foamRun -solver movingMesh)
  set(flowSolver foamRun -solver incompressibleFluid)
elseif(OPENFOAM STREQUAL "1912")
  if(NOT RBM_PLUGIN)
    message("skipped: OpenFOAM not installed (the plugin librbmMotionSolver.so was not built; "
            "scripts/setup.sh installs libopenfoam and fetches its headers)")
    return()
  endif()
  # Debian's OpenFOAM binaries (/usr/bin) find their etc/ files through WM_PROJECT_DIR; nothing
  # else of OpenFOAM's environment is needed.
  if(NOT DEFINED ENV{WM_PROJECT_DIR})
    set(ENV{WM_PROJECT_DIR} /usr/share/openfoam)
  endif()
  set(openfoamEnvironment "")
  set(moveMesh moveDynamicMesh)
  set(flowSolver pimpleFoam)
else()
  message(FATAL_ERROR "OPENFOAM must be 1912 or 13, got '${OPENFOAM}'")
endif()

function(fail message)
  message(FATAL_ERROR "${message}")
endfunction()

function(expectContains text what where)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    fail("${where} does not contain '${what}':\n${text}")
  endif()
endfunction()

function(expectLacks text what where)
  string(FIND "${text}" "${what}" at)
  if(NOT at EQUAL -1)
    fail("${where} contains '${what}':\n${text}")
  endif()
endfunction()

# A fresh copy of a case's inputs; its dynamicMeshDict loads the plugin by its full path.
# OpenFOAM 13: the entries after the FoamFile header go into `mover { type motionSolver; libs
# (...); ... }` (without dynamicFvMesh), movingMesh gets the PIMPLE block it requires,
# incompressibleFluid its physicalProperties and momentumTransport (v1912's transportProperties
# and turbulenceProperties) and decomposePar its <method>Coeffs (v1912 reads coeffs too).
function(prepareCase source destination)
  file(REMOVE_RECURSE ${destination})
  copyCaseInputs(${source} ${destination})
  file(READ ${destination}/constant/dynamicMeshDict text)
  string(REGEX REPLACE "motionSolverLibs[^;]*;" "" text "${text}")
  if(NOT OPENFOAM STREQUAL "13")
    string(REGEX REPLACE "(\n[ \t]*motionSolver[ \t])" "\nmotionSolverLibs (\"${RBM_PLUGIN}\");\\1" text "${text}")
    file(WRITE ${destination}/constant/dynamicMeshDict "${text}")
    return()
  endif()
  string(REGEX REPLACE "dynamicFvMesh[^;]*;" "" text "${text}")
  string(REGEX MATCH "^.*FoamFile[ \t\n]*{[^}]*}" header "${text}")
  if(NOT header)
    fail("${source}/constant/dynamicMeshDict has no FoamFile header")
  endif()
  string(LENGTH "${header}" headerLength)
  string(SUBSTRING "${text}" ${headerLength} -1 body)
  file(WRITE ${destination}/constant/dynamicMeshDict
       "${header}\n\nmover\n{\n    type motionSolver;\n    libs (\"${RBM_PLUGIN}\");\n${body}\n}\n")
  file(READ ${destination}/system/fvSolution text)
  if(NOT text MATCHES "\nPIMPLE")
    file(APPEND ${destination}/system/fvSolution "\nPIMPLE\n{\n}\n")
  endif()
  if(EXISTS ${destination}/constant/transportProperties)
    file(READ ${destination}/constant/transportProperties text)
    string(REGEX MATCH "\nnu[ \t]+([^;]*);" nu "${text}")
    file(WRITE ${destination}/constant/physicalProperties
         "FoamFile { version 2.0; format ascii; class dictionary; object physicalProperties; }\n"
         "viscosityModel constant;\nnu [0 2 -1 0 0 0 0] ${CMAKE_MATCH_1};\n")
    file(REMOVE ${destination}/constant/transportProperties)
  endif()
  # OpenFOAM 13 reads a decomposition method's coefficients from <method>Coeffs only.
  if(EXISTS ${destination}/system/decomposeParDict)
    file(READ ${destination}/system/decomposeParDict text)
    string(REGEX MATCH "\nmethod[ \t]+([a-zA-Z]+);" method "${text}")
    string(REGEX REPLACE "\ncoeffs([ \t\n]*{)" "\n${CMAKE_MATCH_1}Coeffs\\1" text "${text}")
    file(WRITE ${destination}/system/decomposeParDict "${text}")
  endif()
  if(EXISTS ${destination}/constant/turbulenceProperties)
    file(RENAME ${destination}/constant/turbulenceProperties ${destination}/constant/momentumTransport)
  endif()
endfunction()

# Adds entries beside motionSolver: at the end of dynamicMeshDict (v1912), inside the mover
# dictionary, which prepareCase made its last entry (OpenFOAM 13).
function(addMotionSolverEntries case entries)
  file(READ ${case}/constant/dynamicMeshDict text)
  if(OPENFOAM STREQUAL "13")
    string(REGEX REPLACE "}[ \t\n]*$" "${entries}\n}\n" text "${text}")
  else()
    string(APPEND text "\n${entries}\n")
  endif()
  file(WRITE ${case}/constant/dynamicMeshDict "${text}")
endfunction()

# runIn(<case> <expected: 0 or FAIL> <log name> command...): runs in the case folder, output in
# ${name}_out (stdout and stderr together, as OpenFOAM writes errors to either).
function(runIn case expected name)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${case}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  file(WRITE ${case}/log.${name} "${out}")
  if(expected STREQUAL "FAIL")
    if(status EQUAL 0)
      fail("${ARGN} in ${case} succeeded, expected a failure:\n${out}")
    endif()
  elseif(NOT status EQUAL expected)
    fail("${ARGN} in ${case}: exit status ${status}, expected ${expected}:\n${out}")
  endif()
  set(${name}_out "${out}" PARENT_SCOPE)
endfunction()

# runOpenFOAM(<case> <expected> <log name> command...): runIn with OpenFOAM's environment; the
# unit of OpenFOAM 13's time lines ("Time = 0.005s") dropped, so that the checks read both logs.
function(runOpenFOAM case expected name)
  runIn(${case} ${expected} ${name} ${openfoamEnvironment} ${ARGN})
  string(REGEX REPLACE "\nTime = ([0-9.e+-]+)s\n" "\nTime = \\1\n" out "${${name}_out}")
  set(${name}_out "${out}" PARENT_SCOPE)
endfunction()

# comparePoints(<file A> <file B> <tolerance>): the largest point distance must not exceed it.
function(comparePoints a b tolerance)
  execute_process(COMMAND ${RBM_COMPARE_POINTS} ${a} ${b} ${tolerance}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${a} vs ${b}: ${out}${err}")
  if(NOT status EQUAL 0)
    fail("points differ by more than ${tolerance}: ${out}${err}")
  endif()
endfunction()

# The cyclic pairs of the mesh in polyMeshDir moved to movedPoints: u_B = R u_A to tolerance.
function(compareCyclicPairs polyMeshDir movedPoints tolerance)
  execute_process(COMMAND ${RBM_COMPARE_POINTS} --cyclic ${polyMeshDir} ${movedPoints} ${tolerance}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${movedPoints}: ${out}${err}")
  if(NOT status EQUAL 0)
    fail("the cyclic pairs of ${movedPoints} are not together to ${tolerance}: ${out}${err}")
  endif()
endfunction()

# runOnTwoRanks(<case> <expected> <log name> command...): runOpenFOAM of `command -parallel`
# under mpiexec on 2 ranks (RBM_PLUGIN_GATHER passed on to them when set).
function(runOnTwoRanks case expected name)
  # Open MPI refuses root without --allow-run-as-root; 2 ranks on fewer cores need --oversubscribe.
  execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(mpiOptions -np 2 --oversubscribe)
  if(uid STREQUAL "0")
    list(APPEND mpiOptions --allow-run-as-root)
  endif()
  # Open MPI started by its full path (/usr/bin/mpiexec) acts as --prefix /usr and puts /usr/lib
  # first in the ranks' LD_LIBRARY_PATH, where Debian's OpenFOAM v1912 libraries would then
  # shadow OpenFOAM 13's.
  if(OPENFOAM STREQUAL "13")
    list(APPEND mpiOptions --noprefix)
  endif()
  if(DEFINED ENV{RBM_PLUGIN_GATHER})
    list(APPEND mpiOptions -x RBM_PLUGIN_GATHER)
  endif()
  runOpenFOAM(${case} ${expected} ${name} ${MPIEXEC} ${mpiOptions} -x WM_PROJECT_DIR ${ARGN} -parallel)
  set(${name}_out "${${name}_out}" PARENT_SCOPE)
endfunction()

# Runs the flow solver on a decomposed case on 2 ranks; the optional second argument is the
# expected exit (0 by default, FAIL for a run that must stop).
macro(runFlowSolverOnTwoRanks case)
  set(expectedExit 0)
  if(${ARGC} GREATER 1)
    set(expectedExit ${ARGV1})
  endif()
  runOnTwoRanks(${case} ${expectedExit} pimpleFoam ${flowSolver})
endmacro()

function(setControl case keyword value)
  file(READ ${case}/system/controlDict text)
  string(REGEX REPLACE "\n${keyword}[ \t][^;]*;" "\n${keyword} ${value};" text "${text}")
  file(WRITE ${case}/system/controlDict "${text}")
endfunction()

function(setCoefficients case entries)
  file(READ ${case}/constant/dynamicMeshDict text)
  string(REGEX REPLACE "rigidBodyMotionSolverCoeffs[ \t\n]*{[^}]*}"
         "rigidBodyMotionSolverCoeffs\n{\n${entries}\n}" text "${text}")
  file(WRITE ${case}/constant/dynamicMeshDict "${text}")
endfunction()

# Adds one entry to the case's rigidBodyMotionSolverCoeffs, keeping the others.
function(addCoefficient case entry)
  file(READ ${case}/constant/dynamicMeshDict text)
  string(REGEX REPLACE "(rigidBodyMotionSolverCoeffs[ \t\n]*{[^}]*)}" "\\1    ${entry}\n}" text "${text}")
  file(WRITE ${case}/constant/dynamicMeshDict "${text}")
endfunction()

# The log line's figures before the wall time, "sub-steps ... inverted 0", of time `time`:
# rbmMoveMesh prints "Time = 1  sub-steps ... inverted 0"; inside OpenFOAM, which prints its
# own "Time = 1" line, rbm's line is "rigidBodyMotionSolver: sub-steps ... inverted 0" (a line
# starting "Time = " would count every step twice in foamLog-style parsers).
function(stepFigures text time name)
  string(REGEX MATCH "Time = ${time} +(sub-steps[^\n]*inverted [0-9]+)" line "${text}")
  if(line)
    set(${name} "${CMAKE_MATCH_1}" PARENT_SCOPE)
    return()
  endif()
  string(FIND "${text}" "\nTime = ${time}\n" at)
  if(at EQUAL -1)
    fail("no log line for time ${time}:\n${text}")
  endif()
  string(SUBSTRING "${text}" ${at} -1 rest)
  string(SUBSTRING "${rest}" 1 -1 rest)
  string(FIND "${rest}" "\nTime = " next)
  if(NOT next EQUAL -1)
    string(SUBSTRING "${rest}" 0 ${next} rest)
  endif()
  string(REGEX MATCH "\nrigidBodyMotionSolver: (sub-steps[^\n]*inverted [0-9]+)" line "${rest}")
  if(NOT line)
    fail("no rigidBodyMotionSolver line for time ${time}:\n${text}")
  endif()
  set(${name} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

# OpenFOAM's log has exactly `count` lines starting with "Time = " (one per step: rbm's own
# line must not add a second).
function(expectTimeLines text count)
  string(REGEX MATCHALL "\nTime = [^\n]*" lines "\n${text}")
  list(LENGTH lines found)
  if(NOT found EQUAL count)
    fail("${found} lines start with 'Time = ', expected ${count} (one per step):\n${text}")
  endif()
endfunction()

file(MAKE_DIRECTORY ${RBM_WORK_DIR})
set(rbmCase ${RBM_WORK_DIR}/rbmMoveMesh)
set(pluginCase ${RBM_WORK_DIR}/plugin)

# One step of a tutorial with rbmMoveMesh and with moveDynamicMesh + the plugin: the points
# agree to `tolerance`, the log lines up to the wall time are the same, the plugin's header
# says `expected`.
function(compareOneStep tutorial tolerance expected)
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/${tutorial} ${rbmCase})
  prepareCase(${RBM_SOURCE_DIR}/tutorials/${tutorial} ${pluginCase})
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "${expected}" "moveDynamicMesh's log")
  comparePoints(${rbmCase}/1/polyMesh/points.gz ${pluginCase}/1/polyMesh/points.gz ${tolerance})
  stepFigures("${rbmMoveMesh_out}" 1 rbmLine)
  stepFigures("${moveDynamicMesh_out}" 1 pluginLine)
  if(NOT rbmLine STREQUAL pluginLine)
    fail("the plugin's log line differs from rbmMoveMesh's:\n  ${pluginLine}\n  ${rbmLine}")
  endif()
endfunction()

# The oscillating channel (tests/data/openfoamPlugin) meshed by blockMesh for the plugin's run,
# and the same case moved by rbmMoveMesh as the reference.
macro(prepareChannelWithReference)
  set(source ${RBM_SOURCE_DIR}/tests/data/openfoamPlugin/oscillatingChannel)
  prepareCase(${source} ${pluginCase})
  runOpenFOAM(${pluginCase} 0 blockMesh blockMesh)
  file(REMOVE_RECURSE ${rbmCase})
  file(COPY ${pluginCase}/ DESTINATION ${rbmCase})
  # rbmMoveMesh reads the v1912 form of dynamicMeshDict (OpenFOAM 13's mover is prepareCase's).
  file(COPY ${source}/constant/dynamicMeshDict DESTINATION ${rbmCase}/constant)
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
endmacro()

if(MODE STREQUAL "serial2D")
  compareOneStep(naca4415 1e-8 "rigidBodyMotionSolver (rbm): 27150 points, solved in 2D")
  file(READ ${pluginCase}/log.moveDynamicMesh log)
  expectTimeLines("${log}" 1)

elseif(MODE STREQUAL "oneLineSwitch")
  # A user's switch of an OpenFOAM case: the two lines, no rigidBodyMotionSolverCoeffs, and
  # the previous solver's entries left where they were. rbm reads its own block only (absent:
  # the defaults), so the run equals rbmMoveMesh's with the defaults.
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415 ${rbmCase})
  prepareCase(${RBM_SOURCE_DIR}/tutorials/naca4415 ${pluginCase})
  file(READ ${pluginCase}/constant/dynamicMeshDict text)
  string(REGEX REPLACE "rigidBodyMotionSolverCoeffs[ \t\n]*{[^}]*}" "" text "${text}")
  file(WRITE ${pluginCase}/constant/dynamicMeshDict "${text}")
  set(previousSolverEntries "diffusivity  quadratic inverseDistance (airfoil);
displacementLaplacianCoeffs\n{\n    diffusivity quadratic inverseDistance (airfoil);\n}\nmass 2.1;")
  addMotionSolverEntries(${pluginCase} "${previousSolverEntries}")
  file(READ ${pluginCase}/constant/dynamicMeshDict text)
  string(FIND "${text}" "rigidBodyMotionSolverCoeffs" block)
  if(NOT block EQUAL -1)
    fail("the case still has a rigidBodyMotionSolverCoeffs block:\n${text}")
  endif()
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  comparePoints(${rbmCase}/1/polyMesh/points.gz ${pluginCase}/1/polyMesh/points.gz 1e-8)
  # A misspelt entry inside the block is still an error that names it.
  addMotionSolverEntries(${pluginCase} "rigidBodyMotionSolverCoeffs\n{\n    subStep 3;\n}")
  file(REMOVE_RECURSE ${pluginCase}/1)
  runOpenFOAM(${pluginCase} FAIL moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "FOAM FATAL IO ERROR" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "subStep" "moveDynamicMesh's output")

elseif(MODE STREQUAL "interfacePatches")
  # The channel in two blocks joined by a cyclicAMI pair: OpenFOAM's own coupled() is false
  # for AMI patches, yet each side's points would move on their own and the interface would
  # come apart. The plugin refuses the case by the patch's type, naming it, before any step.
  set(source ${RBM_SOURCE_DIR}/tests/data/openfoamPlugin/oscillatingChannel)
  prepareCase(${source} ${pluginCase})
  file(READ ${pluginCase}/system/blockMeshDict text)
  string(REGEX REPLACE "vertices.*$" "" text "${text}")
  string(APPEND text [=[
vertices
(
    (0 0 0) (0.5 0 0) (0.5 1 0) (0 1 0) (0 0 0.1) (0.5 0 0.1) (0.5 1 0.1) (0 1 0.1)
    (0.5 0 0) (1 0 0) (1 1 0) (0.5 1 0) (0.5 0 0.1) (1 0 0.1) (1 1 0.1) (0.5 1 0.1)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (8 16 1) simpleGrading (1 1 1)
    hex (8 9 10 11 12 13 14 15) (8 13 1) simpleGrading (1 1 1)
);
boundary
(
    bottom { type wall; faces ((0 1 5 4) (8 9 13 12)); }
    top    { type patch; faces ((3 7 6 2) (11 15 14 10)); }
    sides  { type wall; faces ((0 4 7 3) (9 10 14 13)); }
    leftInterface  { type cyclicAMI; neighbourPatch rightInterface; transform noOrdering; faces ((1 2 6 5)); }
    rightInterface { type cyclicAMI; neighbourPatch leftInterface; transform noOrdering; faces ((8 12 15 11)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7) (8 11 10 9) (12 13 14 15)); }
);
]=])
  set(interfaceType cyclicAMI)
  if(OPENFOAM STREQUAL "13")
    # OpenFOAM 13 has no cyclicAMI (its non-conformal couplings are made by
    # createNonConformalCouples): a plain cyclic pair, the right block as fine as the left.
    set(interfaceType cyclic)
    string(REPLACE "cyclicAMI" "cyclic" text "${text}")
    string(REPLACE "transform noOrdering; " "" text "${text}")
    string(REPLACE "(8 13 1)" "(8 16 1)" text "${text}")
  endif()
  file(WRITE ${pluginCase}/system/blockMeshDict "${text}")
  file(READ ${pluginCase}/0/pointDisplacement text)
  string(REGEX REPLACE "(frontAndBack)"
         "leftInterface { type ${interfaceType}; }\n    rightInterface { type ${interfaceType}; }\n    \\1" text "${text}")
  file(WRITE ${pluginCase}/0/pointDisplacement "${text}")
  runOpenFOAM(${pluginCase} 0 blockMesh blockMesh)
  if(OPENFOAM STREQUAL "13")
    # A plain cyclic: supported, its two sides (coincident here) moving together.
    runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
    compareCyclicPairs(${pluginCase}/constant/polyMesh ${pluginCase}/0.025/polyMesh/points 1e-12)
    return()
  endif()
  runOpenFOAM(${pluginCase} FAIL moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "FOAM FATAL ERROR" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "patch leftInterface is of type ${interfaceType}" "moveDynamicMesh's output")
  file(GLOB written ${pluginCase}/0.*)
  if(written)
    fail("a refused case wrote ${written}")
  endif()

elseif(MODE STREQUAL "serial3D")
  compareOneStep(cube 1e-9 "solved in 3D")

elseif(MODE STREQUAL "flowSteps")
  prepareChannelWithReference()
  runOpenFOAM(${pluginCase} 0 pimpleFoam ${flowSolver})
  # Five steps, each with the plugin's log line, and pimpleFoam's end.
  foreach(time 0.005 0.01 0.015 0.02 0.025)
    stepFigures("${pimpleFoam_out}" ${time} line)
    expectContains("${line}" "inverted 0" "the log line of time ${time}")
  endforeach()
  expectContains("${pimpleFoam_out}" "\nEnd" "pimpleFoam's log")
  if(NOT EXISTS ${pluginCase}/0.025/meshPhi)
    fail("pimpleFoam wrote no mesh fluxes (0.025/meshPhi): the mesh did not move inside the flow solver")
  endif()
  comparePoints(${rbmCase}/0.025/polyMesh/points ${pluginCase}/0.025/polyMesh/points 1e-8)

elseif(MODE STREQUAL "restart")
  set(source ${RBM_SOURCE_DIR}/tutorials/naca4415Pitching)
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${source} ${rbmCase})
  prepareCase(${source} ${pluginCase})
  set(restartCase ${RBM_WORK_DIR}/restart)
  prepareCase(${source} ${restartCase})
  foreach(case ${rbmCase} ${pluginCase} ${restartCase})
    setControl(${case} endTime 0.15)
    setControl(${case} writeInterval 3)
    # To round-off: a restart has no history for the warm start's predictor and subspace
    # step, so with the default displacementTolerance the two runs stop at different points
    # within it (8.8e-7 apart in the far field, 8.8e-6 of the 0.1 edges there).
    addCoefficient(${case} "displacementTolerance 0;")
  endforeach()
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  foreach(time 0.075 0.15)
    comparePoints(${rbmCase}/${time}/polyMesh/points.gz ${pluginCase}/${time}/polyMesh/points.gz 1e-8)
  endforeach()
  # Stopped after three steps, restarted from the latest written time.
  setControl(${restartCase} endTime 0.075)
  runOpenFOAM(${restartCase} 0 firstPart ${moveMesh})
  setControl(${restartCase} endTime 0.15)
  setControl(${restartCase} startFrom latestTime)
  runOpenFOAM(${restartCase} 0 secondPart ${moveMesh})
  expectContains("${secondPart_out}" "Create mesh for time = 0.075" "the restart's log")
  expectLacks("${secondPart_out}" "Time = 0.025 " "the restart's log (it ran from the start again)")
  stepFigures("${secondPart_out}" 0.1 line)
  comparePoints(${pluginCase}/0.15/polyMesh/points.gz ${restartCase}/0.15/polyMesh/points.gz 1e-8)

elseif(MODE STREQUAL "badCoefficient")
  prepareCase(${RBM_SOURCE_DIR}/tutorials/naca4415 ${pluginCase})
  setCoefficients(${pluginCase} "    coupling bogus;")
  runOpenFOAM(${pluginCase} FAIL moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "FOAM FATAL IO ERROR" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "coupling" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "bogus" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "dynamicMeshDict" "moveDynamicMesh's output")
  if(EXISTS ${pluginCase}/1)
    fail("a run with a bad coefficient wrote time 1")
  endif()
  setCoefficients(${pluginCase} "    writeInvalid maybe;")
  runOpenFOAM(${pluginCase} FAIL moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "FOAM FATAL IO ERROR" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "maybe" "moveDynamicMesh's output")

elseif(MODE STREQUAL "invertedCells")
  # The thesis' uniform weights, linearized in one step, turning the airfoil 40°: cells invert.
  # The untangling stage is off: this test is about the inverted-cell policy of the two front
  # doors, which must agree on the count the solve leaves.
  set(coefficients "    coupling coupled;\n    formulation linearized;\n    weighting uniform;\n    subSteps 1;\n    untangle off;\n    stiffening none;")
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415 ${rbmCase})
  prepareCase(${RBM_SOURCE_DIR}/tutorials/naca4415 ${pluginCase})
  foreach(case ${rbmCase} ${pluginCase})
    setCoefficients(${case} "${coefficients}")
    file(READ ${case}/0/pointDisplacement text)
    string(REPLACE "0.0698131700797732" "0.698131700797732" text "${text}")
    file(WRITE ${case}/0/pointDisplacement "${text}")
  endforeach()
  runIn(${rbmCase} 1 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  string(REGEX MATCH "the moved mesh has ([0-9]+) inverted cell" match "${rbmMoveMesh_out}")
  if(NOT match)
    fail("rbmMoveMesh did not report inverted cells:\n${rbmMoveMesh_out}")
  endif()
  set(count ${CMAKE_MATCH_1})
  runOpenFOAM(${pluginCase} FAIL moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "FOAM FATAL ERROR" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "the moved mesh has ${count} inverted cell" "moveDynamicMesh's output")
  # The advice names the robust choices these coefficients leave out.
  expectContains("${moveDynamicMesh_out}" "formulation nonlinear" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "weighting inverseDistanceSquared" "moveDynamicMesh's output")
  if(EXISTS ${pluginCase}/1)
    fail("a step with inverted cells was written")
  endif()
  setCoefficients(${pluginCase} "${coefficients}\n    writeInvalid yes;")
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "the moved mesh has ${count} inverted cell" "moveDynamicMesh's output")
  expectContains("${moveDynamicMesh_out}" "writeInvalid yes" "moveDynamicMesh's output")

elseif(MODE STREQUAL "aliasName")
  # OpenFOAM's own 6-DoF library registers rigidBodyMotionSolver too; loaded first, it keeps
  # that name, and rbm is selected by its own name with its own block.
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${RBM_SOURCE_DIR}/tutorials/naca4415 ${rbmCase})
  prepareCase(${RBM_SOURCE_DIR}/tutorials/naca4415 ${pluginCase})
  setCoefficients(${rbmCase} "    subSteps 2;")
  setCoefficients(${pluginCase} "    subSteps 2;")
  file(READ ${pluginCase}/constant/dynamicMeshDict text)
  string(REPLACE "(\"${RBM_PLUGIN}\")" "(\"librigidBodyMeshMotion.so\" \"${RBM_PLUGIN}\")" text "${text}")
  string(REGEX REPLACE "motionSolver([ \t]+)rigidBodyMotionSolver;" "motionSolver\\1rbmMotionSolver;" text "${text}")
  string(REPLACE "rigidBodyMotionSolverCoeffs" "rbmMotionSolverCoeffs" text "${text}")
  file(WRITE ${pluginCase}/constant/dynamicMeshDict "${text}")
  expectContains("${text}" "librigidBodyMeshMotion.so" "the alias case's dynamicMeshDict")
  expectContains("${text}" "rbmMotionSolverCoeffs" "the alias case's dynamicMeshDict")
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "Selecting motion solver: rbmMotionSolver" "the plugin's log")
  comparePoints(${rbmCase}/1/polyMesh/points.gz ${pluginCase}/1/polyMesh/points.gz 1e-8)
  stepFigures("${rbmMoveMesh_out}" 1 rbmLine)
  stepFigures("${moveDynamicMesh_out}" 1 pluginLine)
  expectContains("${rbmLine}" "sub-steps  2" "rbmMoveMesh's log line")
  if(NOT rbmLine STREQUAL pluginLine)
    fail("the plugin's log line differs from rbmMoveMesh's:\n  ${pluginLine}\n  ${rbmLine}")
  endif()

elseif(MODE STREQUAL "parallel")
  prepareChannelWithReference()
  runOpenFOAM(${pluginCase} 0 decomposePar decomposePar)
  runFlowSolverOnTwoRanks(${pluginCase})
  expectContains("${pimpleFoam_out}" "gathered from the processors" "pimpleFoam's log")
  foreach(time 0.005 0.01 0.015 0.02 0.025)
    stepFigures("${pimpleFoam_out}" ${time} line)
    expectContains("${line}" "inverted 0" "the log line of time ${time}")
  endforeach()
  expectContains("${pimpleFoam_out}" "\nEnd" "pimpleFoam's log")
  runOpenFOAM(${pluginCase} 0 reconstructPar reconstructPar -latestTime)
  comparePoints(${rbmCase}/0.025/polyMesh/points ${pluginCase}/0.025/polyMesh/points 1e-8)

elseif(MODE STREQUAL "decomposed3D")
  # The fixture as decomposePar left it (its method manual needs the cellDecomposition file it
  # does not keep, so the processor folders are copied, not remade), with the fvSchemes and
  # fvSolution OpenFOAM's programs read.
  set(fixture ${RBM_WORK_DIR}/fixture)
  file(REMOVE_RECURSE ${fixture})
  file(COPY ${RBM_SOURCE_DIR}/tests/data/decomposedTwist/np2/ DESTINATION ${fixture})
  file(COPY ${RBM_SOURCE_DIR}/tutorials/cube/system/fvSchemes ${RBM_SOURCE_DIR}/tutorials/cube/system/fvSolution
       DESTINATION ${fixture}/system)
  file(REMOVE_RECURSE ${rbmCase})
  copyCaseInputs(${fixture} ${rbmCase})
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  set(gatheredCase ${RBM_WORK_DIR}/gathered)
  foreach(case ${pluginCase} ${gatheredCase})
    prepareCase(${fixture} ${case})
    file(COPY ${fixture}/processor0 ${fixture}/processor1 DESTINATION ${case})
  endforeach()
  runOnTwoRanks(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  expectContains("${moveDynamicMesh_out}" "distributed over 2 processors" "moveDynamicMesh's log")
  expectLacks("${moveDynamicMesh_out}" "gathered from the processors" "the distributed run's log")
  set(ENV{RBM_PLUGIN_GATHER} 1)
  runOnTwoRanks(${gatheredCase} 0 gatheredRun ${moveMesh})
  unset(ENV{RBM_PLUGIN_GATHER})
  expectContains("${gatheredRun_out}" "gathered from the processors" "the gathered run's log")
  expectContains("${gatheredRun_out}" "RBM_PLUGIN_GATHER is set" "the gathered run's log")
  foreach(time 0.5 1)
    stepFigures("${rbmMoveMesh_out}" ${time} rbmLine)
    stepFigures("${moveDynamicMesh_out}" ${time} pluginLine)
    string(REGEX MATCH "worst quality.*" rbmQuality "${rbmLine}")
    string(REGEX MATCH "worst quality.*" pluginQuality "${pluginLine}")
    if(NOT rbmQuality STREQUAL pluginQuality)
      fail("time ${time}: the distributed run's quality figures differ from rbmMoveMesh's:\n  ${pluginQuality}\n  ${rbmQuality}")
    endif()
    foreach(case ${pluginCase} ${gatheredCase})
      execute_process(COMMAND ${RBM_COMPARE_POINTS} --decomposed ${fixture}/constant/polyMesh
                              ${rbmCase}/${time}/polyMesh/points ${case} ${time} 2.5e-6
                      RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
      message("${case} at ${time} vs rbmMoveMesh: ${out}${err}")
      if(NOT status EQUAL 0)
        fail("${case} at ${time}: points differ from rbmMoveMesh's by more than 2.5e-6 of their shortest edge: ${out}${err}")
      endif()
    endforeach()
  endforeach()
  # A bad coefficient stops every rank with OpenFOAM's FOAM FATAL IO ERROR naming it, before
  # any step.
  prepareCase(${fixture} ${pluginCase})
  file(COPY ${fixture}/processor0 ${fixture}/processor1 DESTINATION ${pluginCase})
  addMotionSolverEntries(${pluginCase} "rigidBodyMotionSolverCoeffs\n{\n    tolerance bogus;\n}")
  runOnTwoRanks(${pluginCase} FAIL badCoefficient ${moveMesh})
  expectContains("${badCoefficient_out}" "FOAM FATAL IO ERROR" "the bad coefficient's output")
  expectContains("${badCoefficient_out}" "bogus" "the bad coefficient's output")
  file(GLOB written ${pluginCase}/processor0/0.5)
  if(written)
    fail("a run with a bad coefficient wrote ${written}")
  endif()

elseif(MODE STREQUAL "cyclicChannel")
  # The oscillating channel with its slip sides replaced by a translational cyclic pair, left
  # (x = 0) and right (x = 1): the channel is periodic in x.
  set(source ${RBM_SOURCE_DIR}/tests/data/openfoamPlugin/oscillatingChannel)
  prepareCase(${source} ${pluginCase})
  file(READ ${pluginCase}/system/blockMeshDict text)
  string(REPLACE "sides  { type wall; faces ((0 4 7 3) (1 2 6 5)); }"
         "left  { type cyclic; neighbourPatch right; transform translational; separationVector (1 0 0); faces ((0 4 7 3)); }
    right { type cyclic; neighbourPatch left; transform translational; separationVector (-1 0 0); faces ((1 2 6 5)); }"
         text "${text}")
  if(OPENFOAM STREQUAL "13")
    # OpenFOAM 13's separation is the other way round (the neighbour's points to this patch's).
    string(REPLACE "separationVector (1 0 0)" "separation (-1 0 0)" text "${text}")
    string(REPLACE "separationVector (-1 0 0)" "separation (1 0 0)" text "${text}")
    string(REPLACE "transform translational" "transformType translational" text "${text}")
  endif()
  file(WRITE ${pluginCase}/system/blockMeshDict "${text}")
  foreach(field U p pointDisplacement)
    file(READ ${pluginCase}/0/${field} text)
    string(REPLACE "\"(bottom|sides)\"" "bottom { type zeroGradient; }\n    sides" text "${text}")
    string(REGEX REPLACE "sides[ \t\n]*{[^}]*}" "left { type cyclic; }\n    right { type cyclic; }" text "${text}")
    file(WRITE ${pluginCase}/0/${field} "${text}")
  endforeach()
  runOpenFOAM(${pluginCase} 0 blockMesh blockMesh)
  set(parallelCase ${RBM_WORK_DIR}/parallelCase)
  file(REMOVE_RECURSE ${rbmCase} ${parallelCase})
  file(COPY ${pluginCase}/ DESTINATION ${rbmCase})
  file(COPY ${pluginCase}/ DESTINATION ${parallelCase})
  file(COPY ${source}/constant/dynamicMeshDict DESTINATION ${rbmCase}/constant)
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 pimpleFoam ${flowSolver})
  expectContains("${pimpleFoam_out}" "\nEnd" "pimpleFoam's log")
  comparePoints(${rbmCase}/0.025/polyMesh/points ${pluginCase}/0.025/polyMesh/points 1e-8)
  compareCyclicPairs(${pluginCase}/constant/polyMesh ${pluginCase}/0.025/polyMesh/points 1e-12)
  # Decomposed across the channel (bottom half, top half): each cyclic face pair on one
  # processor, so no processorCyclic patch.
  file(READ ${parallelCase}/system/decomposeParDict text)
  string(REPLACE "(2 1 1)" "(1 2 1)" text "${text}")
  file(WRITE ${parallelCase}/system/decomposeParDict "${text}")
  runOpenFOAM(${parallelCase} 0 decomposePar decomposePar)
  runFlowSolverOnTwoRanks(${parallelCase})
  expectContains("${pimpleFoam_out}" "gathered from the processors" "pimpleFoam's log")
  runOpenFOAM(${parallelCase} 0 reconstructPar reconstructPar -latestTime)
  comparePoints(${pluginCase}/0.025/polyMesh/points ${parallelCase}/0.025/polyMesh/points 1e-8)
  compareCyclicPairs(${parallelCase}/constant/polyMesh ${parallelCase}/0.025/polyMesh/points 1e-12)
  if(OPENFOAM STREQUAL "1912")
    # Decomposed along the channel, the interface is split between the processors
    # (processorCyclic patches): refused, naming the patch and the remedy; with
    # `preservePatches (left right);` the pairs stay on one processor and the run equals the
    # serial one (its numbering differs, so to the solver's tolerance, not to the bit).
    file(REMOVE_RECURSE ${parallelCase}/0.025)
    file(GLOB processors ${parallelCase}/processor*)
    file(REMOVE_RECURSE ${processors})
    string(REPLACE "(1 2 1)" "(2 1 1)" text "${text}")
    file(WRITE ${parallelCase}/system/decomposeParDict "${text}")
    runOpenFOAM(${parallelCase} 0 decomposePar decomposePar)
    runFlowSolverOnTwoRanks(${parallelCase} FAIL)
    expectContains("${pimpleFoam_out}" "is a processorCyclic patch" "pimpleFoam's log")
    expectContains("${pimpleFoam_out}" "preservePatches" "pimpleFoam's log")
    file(GLOB processors ${parallelCase}/processor*)
    file(REMOVE_RECURSE ${processors})
    file(WRITE ${parallelCase}/system/decomposeParDict "${text}\npreservePatches (left right);\n")
    runOpenFOAM(${parallelCase} 0 decomposePar decomposePar)
    runFlowSolverOnTwoRanks(${parallelCase} 0)
    runOpenFOAM(${parallelCase} 0 reconstructPar reconstructPar -latestTime)
    comparePoints(${pluginCase}/0.025/polyMesh/points ${parallelCase}/0.025/polyMesh/points 1e-8)
    compareCyclicPairs(${parallelCase}/constant/polyMesh ${parallelCase}/0.025/polyMesh/points 1e-12)
  endif()

elseif(MODE STREQUAL "cyclicSector")
  # A 60° sector of the annulus 1 < r < 2 (one layer, 8 x 16 cells) whose sides are a
  # rotational cyclic pair about z; the inner arc turns (angularOscillatingDisplacement, up to
  # 0.2 rad), the outer one is fixed. moveDynamicMesh: equal to rbmMoveMesh, pairs u_B = R u_A.
  set(source ${RBM_SOURCE_DIR}/tests/data/openfoamPlugin/oscillatingChannel)
  prepareCase(${source} ${pluginCase})
  file(READ ${pluginCase}/system/blockMeshDict text)
  string(REGEX REPLACE "vertices.*$" "" text "${text}")
  string(APPEND text [=[
vertices
(
    (1 0 0) (2 0 0) (1 1.7320508075688772 0) (0.5 0.8660254037844386 0)
    (1 0 0.1) (2 0 0.1) (1 1.7320508075688772 0.1) (0.5 0.8660254037844386 0.1)
);
blocks ( hex (0 1 2 3 4 5 6 7) (8 16 1) simpleGrading (1 1 1) );
edges
(
    arc 1 2 (1.7320508075688772 1 0)     arc 5 6 (1.7320508075688772 1 0.1)
    arc 0 3 (0.8660254037844386 0.5 0)   arc 4 7 (0.8660254037844386 0.5 0.1)
);
boundary
(
    sideA { type cyclic; neighbourPatch sideB; transform rotational; rotationAxis (0 0 1); rotationCentre (0 0 0); faces ((0 1 5 4)); }
    sideB { type cyclic; neighbourPatch sideA; transform rotational; rotationAxis (0 0 1); rotationCentre (0 0 0); faces ((3 7 6 2)); }
    inner { type wall; faces ((0 4 7 3)); }
    outer { type wall; faces ((1 2 6 5)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
]=])
  if(OPENFOAM STREQUAL "13")
    string(REPLACE "transform rotational" "transformType rotational" text "${text}")
  endif()
  file(WRITE ${pluginCase}/system/blockMeshDict "${text}")
  file(WRITE ${pluginCase}/0/pointDisplacement [=[
FoamFile { version 2.0; format ascii; class pointVectorField; object pointDisplacement; }
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    sideA { type cyclic; }
    sideB { type cyclic; }
    inner { type angularOscillatingDisplacement; axis (0 0 1); origin (0 0 0); angle0 0; amplitude 0.2; omega 20; value uniform (0 0 0); }
    outer { type fixedValue; value uniform (0 0 0); }
    frontAndBack { type empty; }
}
]=])
  file(REMOVE ${pluginCase}/0/U ${pluginCase}/0/p)
  runOpenFOAM(${pluginCase} 0 blockMesh blockMesh)
  file(REMOVE_RECURSE ${rbmCase})
  file(COPY ${pluginCase}/ DESTINATION ${rbmCase})
  file(COPY ${source}/constant/dynamicMeshDict DESTINATION ${rbmCase}/constant)
  runIn(${rbmCase} 0 rbmMoveMesh ${RBM_MOVE_MESH} -noVTK)
  runOpenFOAM(${pluginCase} 0 moveDynamicMesh ${moveMesh})
  comparePoints(${rbmCase}/0.025/polyMesh/points ${pluginCase}/0.025/polyMesh/points 1e-8)
  compareCyclicPairs(${pluginCase}/constant/polyMesh ${pluginCase}/0.025/polyMesh/points 1e-12)

else()
  fail("unknown MODE ${MODE}")
endif()

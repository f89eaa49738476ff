# What the tutorial tests that run OpenFOAM need, or a visible skip ("SKIPPED: ...", CTest's skip
# pattern). Both are macros, so their return() ends the calling test script.
#
# rbm_require_openfoam(program...): each of OpenFOAM's programs on the PATH.
macro(rbm_require_openfoam)
  foreach(program ${ARGN})
    find_program(found_${program} ${program})
    if(NOT found_${program})
      message("SKIPPED: OpenFOAM's ${program} not found (apt-get install openfoam, done by scripts/setup.sh)")
      return()
    endif()
  endforeach()
endmacro()

# rbm_find_plugin(): for the tutorial tests that run OpenFOAM with rbm's plugin. Sets `plugin`
# (the path of librbmMotionSolver.so under RBM_BUILD_DIR) and `pluginDir`; without the plugin
# prints "SKIPPED: ..." (CTest's skip pattern) and returns from the calling test script (a macro,
# so its return() is the caller's).
macro(rbm_find_plugin)
  file(GLOB_RECURSE plugin ${RBM_BUILD_DIR}/*librbmMotionSolver.so)
  list(FILTER plugin INCLUDE REGEX "/librbmMotionSolver\\.so$")
  if(NOT plugin)
    message("SKIPPED: rbm's OpenFOAM plugin librbmMotionSolver.so is not built in ${RBM_BUILD_DIR}")
    return()
  endif()
  list(GET plugin 0 plugin)
  get_filename_component(pluginDir ${plugin} DIRECTORY)
endmacro()

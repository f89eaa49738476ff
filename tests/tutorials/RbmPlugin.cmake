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

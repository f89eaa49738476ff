# The checks of rbm's plugin log every flow-tutorial test makes: one line per time step,
# "rigidBodyMotionSolver: sub-steps n ... inverted n", each with 0 inverted cells.
# checkRbmPluginSteps(<solver log text> <expected step count>): calls fail() (the including
# script's) for a missing line or a step with inverted cells.
function(checkRbmPluginSteps text expectedSteps)
  string(REGEX MATCHALL "\nrigidBodyMotionSolver: sub-steps [^\n]* inverted [0-9]+" rbmLines "${text}")
  list(LENGTH rbmLines rbmCount)
  if(NOT rbmCount EQUAL expectedSteps)
    fail("rbm's plugin logged ${rbmCount} steps, expected ${expectedSteps}")
  endif()
  foreach(line IN LISTS rbmLines)
    if(NOT line MATCHES " inverted 0$")
      fail("rbm's plugin reports inverted cells: ${line}")
    endif()
  endforeach()
endfunction()

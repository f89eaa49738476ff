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

# checkMeshLogQuality(<checkMesh output of the written times> <bound in degrees> <var>): no
# negative volume, every time's max non-orthogonality within the bound (fail() otherwise);
# <var> receives the largest.
function(checkMeshLogQuality out bound resultVar)
  if(out MATCHES "negative volume")
    fail("checkMesh found negative-volume (inverted) cells:\n${out}")
  endif()
  string(REGEX MATCHALL "non-orthogonality Max: [0-9.]+" nonOrthogonality "${out}")
  set(largest 0)
  foreach(entry IN LISTS nonOrthogonality)
    string(REGEX REPLACE ".*: " "" value "${entry}")
    if(value GREATER bound)
      fail("max non-orthogonality ${value} > ${bound} degrees")
    endif()
    if(value GREATER largest)
      set(largest ${value})
    endif()
  endforeach()
  set(${resultVar} ${largest} PARENT_SCOPE)
endfunction()

# copyCaseInputs(<source case> <destination case>): copies an OpenFOAM case's inputs only
# (0/, constant/, system/), never the time folders, VTK/ or postProcessing/ that an earlier
# run wrote into the source. The README's first command runs tutorials/naca4415 in place
# before the suite runs, so a test that copied the whole folder would start from that run's
# results (issue 13).
function(copyCaseInputs source destination)
  if(NOT EXISTS ${source}/system/controlDict)
    message(FATAL_ERROR "copyCaseInputs: ${source} is not a case (no system/controlDict)")
  endif()
  file(MAKE_DIRECTORY ${destination})
  foreach(part 0 constant system)
    file(COPY ${source}/${part} DESTINATION ${destination})
  endforeach()
endfunction()

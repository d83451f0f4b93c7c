# Driver for one render regression test, run as
#     cmake -DRAYSHADE=... -DIMGDIFF=... -DSCENE=... -DREFERENCE=... -DOUTPUT=... -DWORKDIR=...
#           [-DRENDER_ARGS=a;b;...] [-DTHRESHOLDS_FILE=... -DTHRESHOLDS_SCENE=...
#           -DTHRESHOLDS_RESOLUTION=...] [-DIMGDIFF_ARGS=a;b;...] [-DUPDATE_REFERENCE=ON]
#           -P run_render_test.cmake
# (see RenderTest.cmake). Any failure ends the script with FATAL_ERROR, i.e. a non-zero exit.
cmake_minimum_required(VERSION 3.20)

foreach(required RAYSHADE IMGDIFF SCENE REFERENCE OUTPUT WORKDIR)
  if(NOT DEFINED ${required} OR "${${required}}" STREQUAL "")
    message(FATAL_ERROR "run_render_test: -D${required}=... is required")
  endif()
endforeach()

get_filename_component(outputDir "${OUTPUT}" DIRECTORY)
get_filename_component(outputName "${OUTPUT}" NAME_WLE)
set(diffImage "${outputDir}/${outputName}.diff.png")
set(referenceCopy "${outputDir}/${outputName}.ref.png")
file(MAKE_DIRECTORY "${outputDir}")
# Results of an earlier run must neither pass for this one nor confuse its review.
file(REMOVE "${OUTPUT}" "${diffImage}" "${referenceCopy}")

execute_process(COMMAND "${RAYSHADE}" -q ${RENDER_ARGS} -O "${OUTPUT}" "${SCENE}"
                WORKING_DIRECTORY "${WORKDIR}"
                RESULT_VARIABLE renderStatus)
if(NOT renderStatus EQUAL 0)
  message(FATAL_ERROR "rayshade failed (${renderStatus}) on ${SCENE}")
endif()
if(NOT EXISTS "${OUTPUT}")
  message(FATAL_ERROR "rayshade exited 0 but wrote no ${OUTPUT}")
endif()

if(UPDATE_REFERENCE)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E copy "${OUTPUT}" "${REFERENCE}"
                  RESULT_VARIABLE copyStatus)
  if(NOT copyStatus EQUAL 0)
    message(FATAL_ERROR "cannot update the reference ${REFERENCE}")
  endif()
  message(STATUS "updated reference ${REFERENCE}")
  return()
endif()

set(thresholdOptions "")
if(NOT "${THRESHOLDS_SCENE}" STREQUAL "")
  set(thresholdOptions --thresholds "${THRESHOLDS_FILE}" "${THRESHOLDS_SCENE}"
                       "${THRESHOLDS_RESOLUTION}")
endif()
execute_process(COMMAND "${IMGDIFF}" ${thresholdOptions} ${IMGDIFF_ARGS} --diff "${diffImage}"
                        "${OUTPUT}" "${REFERENCE}"
                RESULT_VARIABLE diffStatus)
if(NOT diffStatus EQUAL 0)
  if(EXISTS "${REFERENCE}")
    execute_process(COMMAND "${CMAKE_COMMAND}" -E copy "${REFERENCE}" "${referenceCopy}")
  endif()
  if(diffStatus EQUAL 1)
    message(FATAL_ERROR "image differs from ${REFERENCE}; "
                        "review ${OUTPUT}, ${referenceCopy} and ${diffImage}")
  endif()
  message(FATAL_ERROR "imgdiff could not compare ${OUTPUT} with ${REFERENCE} (${diffStatus})")
endif()

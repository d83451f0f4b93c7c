# Render regression tests: one CTest test renders a scene with the `rayshade` target and
# compares the image with a reference through the `imgdiff` target.
#
#   add_render_test(NAME name SCENE scene.ray REFERENCE reference.png
#                   [ARGS rayshade-options...] [WORKDIR dir]
#                   [THRESHOLDS scene resolution] [IMGDIFF_ARGS imgdiff-options...]
#                   [LABELS label...])
#
# The test runs, in WORKDIR (default: the scene's directory, so relative #includes and image
# files resolve as they did for the reference),
#     rayshade -q ARGS... -O <build>/render_tests/<name>.png scene.ray
# then
#     imgdiff [--thresholds RAYSHADE_THRESHOLDS_FILE scene resolution] [IMGDIFF_ARGS...]
#             --diff <build>/render_tests/<name>.diff.png <output> reference.png
# and fails if either exits non-zero. Without THRESHOLDS imgdiff's built-in defaults apply
# (the "default any" row of the shared table). THRESHOLDS takes the scene name and
# resolution (a number for a -R run, "default" for the scene's own size) of a row of
# RAYSHADE_THRESHOLDS_FILE. IMGDIFF_ARGS passes further imgdiff options, e.g. stricter
# single-metric thresholds (--max 0.004) for self-regression; they override the table's.
# On a failed comparison the reference is copied beside the output as <name>.ref.png, so
# output, reference and heat map can be reviewed together.
#
# Configured with -DRAYSHADE_UPDATE_REFERENCES=ON, the test instead renders and copies the
# output over REFERENCE (which must then be writable: our own references, not the original
# program's).
#
# Paths may be relative to the calling CMakeLists.txt's directory. ARGS and IMGDIFF_ARGS
# elements may not contain ';'. The tests carry the label "regression" plus LABELS.
include_guard(GLOBAL)

set(RAYSHADE_THRESHOLDS_FILE "${RAYSHADE_SHARED_DIR}/reference/thresholds.tsv" CACHE FILEPATH
    "Per-scene imgdiff thresholds used by add_render_test(... THRESHOLDS scene res)")

set(_RAYSHADE_RENDER_TEST_DRIVER "${CMAKE_CURRENT_LIST_DIR}/run_render_test.cmake")

function(add_render_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME;SCENE;REFERENCE;WORKDIR"
                        "ARGS;THRESHOLDS;IMGDIFF_ARGS;LABELS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "add_render_test: unexpected arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  foreach(required NAME SCENE REFERENCE)
    if(NOT arg_${required})
      message(FATAL_ERROR "add_render_test: ${required} is required")
    endif()
  endforeach()
  set(thresholdScene "")
  set(thresholdResolution "")
  if(DEFINED arg_THRESHOLDS)
    list(LENGTH arg_THRESHOLDS count)
    if(NOT count EQUAL 2)
      message(FATAL_ERROR
              "add_render_test(${arg_NAME}): THRESHOLDS takes a scene name and a resolution")
    endif()
    list(GET arg_THRESHOLDS 0 thresholdScene)
    list(GET arg_THRESHOLDS 1 thresholdResolution)
  endif()

  get_filename_component(scene "${arg_SCENE}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(reference "${arg_REFERENCE}" ABSOLUTE
                         BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(arg_WORKDIR)
    get_filename_component(workdir "${arg_WORKDIR}" ABSOLUTE
                           BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  else()
    get_filename_component(workdir "${scene}" DIRECTORY)
  endif()
  set(output "${CMAKE_CURRENT_BINARY_DIR}/render_tests/${arg_NAME}.png")

  # A list cannot pass through add_test as one argument: its ';' would split it. Each ';'
  # becomes $<SEMICOLON>, which is expanded only when the test command is generated.
  string(REPLACE ";" "$<SEMICOLON>" renderArgs "${arg_ARGS}")
  string(REPLACE ";" "$<SEMICOLON>" imgdiffArgs "${arg_IMGDIFF_ARGS}")

  add_test(NAME ${arg_NAME}
           COMMAND ${CMAKE_COMMAND}
                   "-DRAYSHADE=$<TARGET_FILE:rayshade>"
                   "-DIMGDIFF=$<TARGET_FILE:imgdiff>"
                   "-DSCENE=${scene}"
                   "-DREFERENCE=${reference}"
                   "-DOUTPUT=${output}"
                   "-DWORKDIR=${workdir}"
                   "-DRENDER_ARGS=${renderArgs}"
                   "-DIMGDIFF_ARGS=${imgdiffArgs}"
                   "-DTHRESHOLDS_FILE=${RAYSHADE_THRESHOLDS_FILE}"
                   "-DTHRESHOLDS_SCENE=${thresholdScene}"
                   "-DTHRESHOLDS_RESOLUTION=${thresholdResolution}"
                   "-DUPDATE_REFERENCE=${RAYSHADE_UPDATE_REFERENCES}"
                   -P "${_RAYSHADE_RENDER_TEST_DRIVER}")
  set_tests_properties(${arg_NAME} PROPERTIES LABELS "regression;${arg_LABELS}")
endfunction()

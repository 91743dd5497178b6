# Writes <OUTPUT> with the source tree's revision (git describe), run at every
# build by the target glide_version; configure_file rewrites the file only
# when the revision changed, so an unchanged tree recompiles nothing.
# Without git (a source archive) the revision is "unknown".
set(GLIDE_REVISION "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  # Only the tree's own repository (not one that a source archive was
  # unpacked into).
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --show-toplevel
    OUTPUT_VARIABLE _top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
endif()
if(GIT_FOUND AND _top)
  get_filename_component(_top "${_top}" REALPATH)
  get_filename_component(_source "${SOURCE_DIR}" REALPATH)
endif()
if(GIT_FOUND AND _top AND _top STREQUAL _source)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} describe --always --dirty --tags
    OUTPUT_VARIABLE _revision OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE _status)
  if(_status EQUAL 0 AND _revision)
    set(GLIDE_REVISION "${_revision}")
  endif()
endif()
configure_file(${SOURCE_DIR}/cmake/version.h.in ${OUTPUT} @ONLY)

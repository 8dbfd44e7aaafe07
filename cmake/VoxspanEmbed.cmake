# voxspan_embed_files(<target> NAME <fn> FILES <file>...)
# Embeds text files (GLSL) into <target> at build time. The generated source defines
#   std::span<const voxspan::EmbeddedFile> voxspan::embedded::<fn>();
# whose entries are named by their path relative to the repository root
# (e.g. "render/gl/probe.comp"). Editing a file regenerates the source.
set(VOXSPAN_EMBED_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/embed_files.cmake")

function(voxspan_embed_files target)
  cmake_parse_arguments(ARG "" "NAME" "FILES" ${ARGN})
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_${target}_${ARG_NAME}.cpp")
  set(abs_files "")
  foreach(f IN LISTS ARG_FILES)
    get_filename_component(a "${f}" ABSOLUTE)
    list(APPEND abs_files "${a}")
  endforeach()
  string(REPLACE ";" "|" files_arg "${abs_files}")
  add_custom_command(OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNAME=${ARG_NAME} -DBASE=${PROJECT_SOURCE_DIR}
            "-DFILES=${files_arg}" -P "${VOXSPAN_EMBED_SCRIPT}"
    DEPENDS ${abs_files} "${VOXSPAN_EMBED_SCRIPT}"
    COMMENT "Embedding ${ARG_NAME}" VERBATIM)
  target_sources(${target} PRIVATE "${out}")
endfunction()

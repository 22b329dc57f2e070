# sandtin_embed_shaders(<target> <shader files...>)
# Compiles each GLSL file to SPIR-V with glslangValidator at build time and adds a generated
# header "<name>_<stage>.spv.h" (a `const uint32_t kSpv_<name>_<stage>[]` array) to the
# target's include path, so the binary embeds its shaders. A compile error fails the build
# with glslang's "ERROR: <file>:<line>: ..." message. Shared by engine/gpu (compute shaders)
# and the renderer (shaders/render).
find_program(SANDTIN_GLSLANG glslangValidator REQUIRED)

function(sandtin_embed_shaders target)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  # Every shader depends on every include file: few files, and no stale SPIR-V.
  file(GLOB includes CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/shaders/*.glsl)
  foreach(src IN LISTS ARGN)
    get_filename_component(abs ${src} ABSOLUTE)
    get_filename_component(name ${src} NAME_WE)
    get_filename_component(ext ${src} EXT)
    string(SUBSTRING ${ext} 1 -1 stage)
    set(header ${out_dir}/${name}_${stage}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${SANDTIN_GLSLANG} -V --target-env vulkan1.2 --quiet
              -I${PROJECT_SOURCE_DIR}/shaders --vn kSpv_${name}_${stage} -o ${header} ${abs}
      DEPENDS ${abs} ${includes}
      COMMENT "glslang ${src}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  target_sources(${target} PRIVATE ${headers})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()

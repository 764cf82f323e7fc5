# Turns each kernel source into a C++ string (raw literal) in one generated file, with a
# lookup function gridrt::embeddedKernelSource(name). Headers under kernels/common are
# embedded too so that '#include' inside kernels resolves without the source tree.
function(gridrt_embed_kernels output)
  set(sources ${ARGN})
  # A list argument must reach the script as one word: escape its separators.
  string(REPLACE ";" "\\;" sources_arg "${sources}")
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} "-DSOURCES=${sources_arg}"
            -DROOT=${CMAKE_SOURCE_DIR}/kernels -P ${CMAKE_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    DEPENDS ${sources} ${CMAKE_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    COMMENT "Embedding OpenCL kernel sources")
endfunction()

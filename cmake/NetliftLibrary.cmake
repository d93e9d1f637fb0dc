# netlift_add_library(name SOURCES ... [DEPENDS ...])
# One library per folder; dependencies are declared, and only point downward
# (tools -> backends -> engine -> passes/frontends -> ir).
function(netlift_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_link_libraries(${name} PUBLIC ${ARG_DEPENDS})
endfunction()

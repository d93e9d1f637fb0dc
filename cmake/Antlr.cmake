# ANTLR4 support: generate C++ from a .g4 grammar at build time.
#
# The Debian `antlr4` tool is 4.7.2 and the runtime library 4.9; the 4.7.2
# generator's C++ output compiles and runs against the 4.9 runtime (proved by
# the grammar smoke test in test/unit/antlr). Generated code lives only in the
# build directory.
find_program(NETLIFT_JAVA java REQUIRED)
find_file(NETLIFT_ANTLR_JAR antlr4.jar PATHS /usr/share/java REQUIRED)
set(NETLIFT_ANTLR_CLASSPATH
    "/usr/share/java/stringtemplate4.jar:/usr/share/java/antlr4.jar:/usr/share/java/antlr4-runtime.jar:/usr/share/java/antlr3-runtime.jar:/usr/share/java/treelayout.jar")

# netlift_antlr_grammar(<target> <grammar.g4> [VISITOR] [LISTENER]
#                       [PARSER_ONLY] [NAMESPACE ns]
#                       [TOKENS_FROM target VOCAB grammar])
# Creates a static library <target> holding the generated lexer/parser,
# linked against the ANTLR runtime; its include directory is the generated
# folder. PARSER_ONLY is for a `parser grammar` whose tokens come from a
# hand-written lexer: the generated recognizer is then named after the
# grammar itself (ST.g4 gives class ST). TOKENS_FROM names another grammar
# target whose .tokens file this grammar's `tokenVocab` option reads (IL.g4
# shares ST's token types, so one lexer serves both).
function(netlift_antlr_grammar target grammar)
  cmake_parse_arguments(ARG "VISITOR;LISTENER;PARSER_ONLY"
                        "NAMESPACE;TOKENS_FROM;VOCAB" "" ${ARGN})
  get_filename_component(g4 ${grammar} ABSOLUTE)
  get_filename_component(name ${grammar} NAME_WE)
  set(outdir ${CMAKE_CURRENT_BINARY_DIR}/${target}_gen)
  if(ARG_PARSER_ONLY)
    set(outputs ${outdir}/${name}.cpp ${outdir}/${name}.h
                ${outdir}/${name}.tokens)
  else()
    set(outputs ${outdir}/${name}Lexer.cpp ${outdir}/${name}Parser.cpp
                ${outdir}/${name}Lexer.h ${outdir}/${name}Parser.h)
  endif()
  set(flags -no-listener -no-visitor)
  if(ARG_NAMESPACE)
    list(APPEND flags -package ${ARG_NAMESPACE})
  endif()
  set(extra_depends)
  if(ARG_TOKENS_FROM)
    set(vocabdir ${CMAKE_CURRENT_BINARY_DIR}/${ARG_TOKENS_FROM}_gen)
    list(APPEND flags -lib ${vocabdir})
    # The target orders the build; the file reruns ANTLR when it changes.
    set(extra_depends ${ARG_TOKENS_FROM} ${vocabdir}/${ARG_VOCAB}.tokens)
  endif()
  if(ARG_VISITOR)
    list(APPEND outputs ${outdir}/${name}Visitor.cpp
         ${outdir}/${name}BaseVisitor.cpp)
    list(REMOVE_ITEM flags -no-visitor)
    list(APPEND flags -visitor)
  endif()
  if(ARG_LISTENER)
    list(APPEND outputs ${outdir}/${name}Listener.cpp
         ${outdir}/${name}BaseListener.cpp)
    list(REMOVE_ITEM flags -no-listener)
    list(APPEND flags -listener)
  endif()
  add_custom_command(
    OUTPUT ${outputs}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${outdir}
    COMMAND ${NETLIFT_JAVA} -cp ${NETLIFT_ANTLR_CLASSPATH} org.antlr.v4.Tool
            -Dlanguage=Cpp ${flags} -o ${outdir} -Xexact-output-dir ${g4}
    DEPENDS ${g4} ${extra_depends}
    COMMENT "ANTLR4: generating C++ for ${name}.g4"
    VERBATIM)
  add_library(${target} STATIC ${outputs})
  target_include_directories(${target} SYSTEM PUBLIC ${outdir}
                             ${ANTLR4_INCLUDE_DIR})
  # Generated code is not ours to warn about. The 4.7.2 generator writes
  # u8"" literals into std::string initialisers, which C++20 types as
  # char8_t: -fno-char8_t restores the C++17 meaning for these files only.
  target_compile_options(${target} PRIVATE -w -fno-char8_t)
  target_link_libraries(${target} PUBLIC antlr4_shared)
endfunction()

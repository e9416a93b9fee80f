# docs/parameters.md is generated from the parameter declarations (param_table.hpp): this test
# fails when the file and the code disagree. Regenerate with
#   build/bin/plumage plugins describe --markdown --out docs/parameters.md
execute_process(COMMAND ${PLUMAGE} plugins describe --markdown OUTPUT_VARIABLE generated RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plumage plugins describe --markdown failed (${rc})")
endif()
file(READ ${DOC} shipped)
if(NOT generated STREQUAL shipped)
  file(WRITE ${WORK}/parameters.generated.md "${generated}")
  message(FATAL_ERROR "docs/parameters.md differs from the declarations in the code (generated copy: "
          "${WORK}/parameters.generated.md); regenerate it with: plumage plugins describe --markdown --out docs/parameters.md")
endif()

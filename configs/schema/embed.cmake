# cupola_embed_config_schemas(<file>): writes <file>, the lines {"<name>", R"(<text>)"}, one per
# <name>.schema.json here, which common/config/config_schema.cpp includes; the configure step
# re-runs when a schema changes. Used by common/CMakeLists.txt and fuzz/config_fuzz.cmake.
set(CUPOLA_SCHEMA_DIR ${CMAKE_CURRENT_LIST_DIR})
function(cupola_embed_config_schemas out_file)
  set(text "")
  foreach(schema cluster scene show devices)
    set(schema_file ${CUPOLA_SCHEMA_DIR}/${schema}.schema.json)
    file(READ ${schema_file} schema_json)
    string(APPEND text "{\"${schema}\", R\"cupola_schema(${schema_json})cupola_schema\"},\n")
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${schema_file})
  endforeach()
  file(CONFIGURE OUTPUT ${out_file} CONTENT "${text}" @ONLY)
endfunction()

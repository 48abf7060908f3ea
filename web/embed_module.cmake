# embed_module.cmake: writes the WebAssembly module WASM as OUT, a classic script that
# sets window.exactpixelsModule to the module's bytes in base64 (coreutils' base64).
execute_process(COMMAND ${BASE64} -w0 ${WASM} OUTPUT_VARIABLE text RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "base64 ${WASM} failed")
endif()
file(SIZE ${WASM} size)
file(WRITE ${OUT}.tmp "// The book's library compiled to WebAssembly (web/live_figures.cpp), "
  "${size} bytes, as base64.\nwindow.exactpixelsModule = \"${text}\";\n")
file(RENAME ${OUT}.tmp ${OUT})

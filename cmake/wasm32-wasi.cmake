# Compiling for WebAssembly (the HTML book's live figures, web/) with Debian's clang-14
# for wasm32-wasi: packages clang-14, lld-14, wasi-libc, libc++-14-dev-wasm32 and
# libclang-rt-14-dev-wasm32 (README.md's install line). Debian's clang finds the WASI
# sysroot (/usr/lib/wasm32-wasi, /usr/include/wasm32-wasi) without --sysroot. Nothing is
# downloaded: no emscripten, no ports.
# CMake 3.25 knows no WASI platform; Generic is a system without an operating system's
# conventions, which is what a reactor module needs.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR wasm32)
set(CMAKE_C_COMPILER clang-14)
set(CMAKE_CXX_COMPILER clang++-14)
set(CMAKE_C_COMPILER_TARGET wasm32-wasi)
set(CMAKE_CXX_COMPILER_TARGET wasm32-wasi)
# The compiler check links a program with a main(); a reactor module has none, so only
# compile it.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

// no_exception_runtime.cpp: what a `throw` calls, for the WebAssembly build of the live
// figures. Debian's wasm32 libc++abi is built without exceptions, so it has no
// __cxa_throw; and WebAssembly (without the exception-handling proposal, which clang-14's
// wasm32-wasi does not use) cannot unwind. The library throws Error only on bad input,
// which live_figures.cpp refuses before calling it, so a throw here is a bug: it traps,
// and the page reports the trap as an uncaught exception (the interactive tests fail on
// any).
#include <cstddef>

extern "C" {

void* __cxa_allocate_exception(std::size_t) noexcept {
    __builtin_trap();
}

void __cxa_throw(void*, void*, void (*)(void*)) {
    __builtin_trap();
}

} // extern "C"

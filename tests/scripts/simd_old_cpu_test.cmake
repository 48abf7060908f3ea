# simd_old_cpu_test.cmake: the program runs on an x86-64 CPU with nothing beyond SSE4.2
# (QEMU's user-mode emulator posing as a Nehalem, which has no AVX), picks SSE2 there
# by itself and draws the scene as this machine's widest variant draws it, byte for
# byte (the scene with the exact mapper everywhere); forcing AVX2 there is refused with exit 2. Code compiled for AVX2 or AVX-512
# reaching a shared function would stop the emulated program with an illegal
# instruction (CTest `simd_old_cpu`).
#   cmake -DQEMU=qemu-x86_64 -DCLI=.../exactpixels -DSCENE=.../x.toml -DWORK=... -P ...
cmake_minimum_required(VERSION 3.25)
foreach(required QEMU CLI SCENE WORK)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "simd_old_cpu_test.cmake: -D${required}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
# The scene with the exact mapper on every span, so that the vector kernels draw it all.
file(READ ${SCENE} text)
string(REGEX REPLACE "mapper = \"auto\"" "mapper = \"exact\"" text "${text}")
if(NOT text MATCHES "mapper = \"exact\"")
  message(FATAL_ERROR "${SCENE} has no mapper = \"auto\" to replace")
endif()
file(WRITE ${WORK}/scene.toml "${text}")
set(SCENE ${WORK}/scene.toml)
unset(ENV{EXACTPIXELS_SIMD})
execute_process(COMMAND ${CLI} render ${SCENE} -o ${WORK}/native.png
  RESULT_VARIABLE native ERROR_VARIABLE native_err)
if(NOT native EQUAL 0)
  message(FATAL_ERROR "native render failed (${native}): ${native_err}")
endif()
execute_process(COMMAND ${QEMU} -cpu Nehalem ${CLI} render ${SCENE} -o ${WORK}/old.png
  RESULT_VARIABLE old ERROR_VARIABLE old_err)
if(NOT old EQUAL 0)
  message(FATAL_ERROR "render on an emulated Nehalem failed (${old}): ${old_err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/native.png ${WORK}/old.png
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the emulated Nehalem's picture differs from this machine's")
endif()
set(ENV{EXACTPIXELS_SIMD} avx2)
execute_process(COMMAND ${QEMU} -cpu Nehalem ${CLI} --version
  RESULT_VARIABLE forced ERROR_VARIABLE forced_err)
if(NOT forced EQUAL 2 OR NOT forced_err MATCHES "^exactpixels: EXACTPIXELS_SIMD=avx2: ")
  message(FATAL_ERROR "EXACTPIXELS_SIMD=avx2 on a Nehalem: exit ${forced}, '${forced_err}'")
endif()
message("Nehalem (emulated): same picture; EXACTPIXELS_SIMD=avx2 refused")

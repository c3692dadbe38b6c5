# Installs the plugin component of the build tree into a fresh prefix, then
# builds tests/capi/find_package against it twice: with find_package(Geocean)
# and with pkg-config. Both consumers must run and pass.
#   cmake -DBUILD_DIR=... -DCONSUMER_DIR=... -DWORK_DIR=... -DC_COMPILER=... -P find_package_test.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

# A sanitizer build (GEOCEAN_SANITIZE) installs instrumented libraries: the
# consumer is compiled and linked with the same -fsanitize flags, as a
# consumer of such a build must be.
load_cache("${BUILD_DIR}" READ_WITH_PREFIX "" GEOCEAN_SANITIZE_FLAGS_CACHED)
set(san_flags "${GEOCEAN_SANITIZE_FLAGS_CACHED}")
list(JOIN san_flags " " san_string)
if(san_flags)
  message(STATUS "consumer built with ${san_string}")
endif()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --component plugin)
foreach(f include/geocean/geocean_ocean.h lib/libgeocean_ocean.so.1 lib/cmake/Geocean/GeoceanConfig.cmake
          lib/cmake/Geocean/GeoceanConfigVersion.cmake lib/pkgconfig/geocean.pc share/geocean/data/landmask_5m.tif)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "install is missing ${f}")
  endif()
endforeach()

# The consumer must find the data beside the library, not through the environment.
unset(ENV{GEOCEAN_DATA})
run(${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${WORK_DIR}/consumer" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_C_FLAGS=${san_string}" "-DCMAKE_EXE_LINKER_FLAGS=${san_string}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/consumer")

# pkg-config: flags from the installed geocean.pc only.
set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
execute_process(COMMAND pkg-config --cflags --libs geocean RESULT_VARIABLE rc OUTPUT_VARIABLE flags
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs geocean failed")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${C_COMPILER} -std=c99 -pedantic -Werror ${san_flags} "${CONSUMER_DIR}/consumer.c" ${flags} -o "${WORK_DIR}/consumer_pc")
set(ENV{LD_LIBRARY_PATH} "${prefix}/lib")
run("${WORK_DIR}/consumer_pc")

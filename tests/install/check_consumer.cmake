# Installs the build into a fresh prefix under the build tree, then builds examples/cpp_consumer
# against it twice, with find_package(omninav) and with pkg-config's omninav.pc, runs both, and
# runs the installed program on what they wrote (so that it finds its installed configuration).
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DCXX=... -DGENERATOR=... -P check_consumer.cmake
foreach(variable BUILD_DIR SOURCE_DIR CXX GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "check_consumer.cmake: -D${variable}=... missing")
  endif()
endforeach()

set(work ${BUILD_DIR}/install-check)
set(prefix ${work}/prefix)
file(REMOVE_RECURSE ${work})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file bin/omninav share/omninav/config/memory.yaml include/omninav/memory/localisation.hpp
             lib/pkgconfig/omninav.pc lib/cmake/omninav/omninavConfig.cmake
             share/bash-completion/completions/omninav)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install holds no ${file}")
  endif()
endforeach()

# find_package(omninav)
run("configuring the example" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/cpp_consumer
    -B ${work}/consumer -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix})
run("building the example" ${CMAKE_COMMAND} --build ${work}/consumer)
run("running the example" ${work}/consumer/omninav_consumer ${work}/out
    ${prefix}/share/omninav/config)
message(STATUS "find_package build: ${output}")

# The installed program with its installed configuration on the example's map.
run("omninav localise" ${prefix}/bin/omninav localise ${work}/out/map.vmem ${work}/out/query.png
    --format csv)
if(NOT output MATCHES "query\\.png,1,[0-9.]+,[0-9.]+,(89\\.[5-9]|90\\.[0-4])")
  message(FATAL_ERROR "installed omninav localise: expected place 1 turned 90 degrees:\n${output}")
endif()

# pkg-config --cflags --libs omninav
find_program(pkg_config pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
run("pkg-config" ${pkg_config} --cflags --libs omninav)
separate_arguments(flags UNIX_COMMAND "${output}")
run("building the example with pkg-config" ${CXX} ${SOURCE_DIR}/examples/cpp_consumer/main.cpp
    ${flags} -o ${work}/omninav_consumer_pc)
run("running the pkg-config build" ${work}/omninav_consumer_pc ${work}/out-pc)
message(STATUS "pkg-config build: ${output}")

# The Python package as `cmake --install` lays it out (python/CMakeLists.txt): imported from the
# prefix alone, it finds the configuration installed inside it.
if(DEFINED PYTHON AND DEFINED PYTHON_INSTALL_DIR)
  set(ENV{PYTHONPATH} ${prefix}/${PYTHON_INSTALL_DIR})
  unset(ENV{OMNINAV_CONFIG_DIR})
  run("importing the installed module" ${PYTHON} -c
      "import omninav\nprint(omninav.__version__)\nprint(omninav.default_config_dir())\nprint(omninav.CompassConfig.load().sampling)")
  if(NOT output MATCHES "${prefix}/${PYTHON_INSTALL_DIR}/omninav/config\n")
    message(FATAL_ERROR "the installed module's configuration is not its own:\n${output}")
  endif()
  message(STATUS "installed Python module: ${output}")
endif()

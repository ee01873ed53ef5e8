# `cmake --install build --prefix P`: the libraries (each omninav_library() installs itself and
# its public headers), the program, the default configuration, a CMake package (find_package(
# omninav) gives omninav::core, omninav::memory, ...) and a pkg-config file (omninav.pc).
include(CMakePackageConfigHelpers)

install(TARGETS omninav RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Where the program looks for it: <prefix>/share/omninav/config beside <prefix>/bin.
install(DIRECTORY config/ DESTINATION ${CMAKE_INSTALL_DATADIR}/omninav/config)

set(omninav_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/omninav)
install(EXPORT omninav-targets NAMESPACE omninav:: FILE omninavTargets.cmake
        DESTINATION ${omninav_cmake_dir})
configure_package_config_file(cmake/omninavConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/omninavConfig.cmake
                              INSTALL_DESTINATION ${omninav_cmake_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/omninavConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/omninavConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/omninavConfigVersion.cmake
        DESTINATION ${omninav_cmake_dir})

# The static libraries in an order a linker takes (each before those it uses). The list must name
# every omninav_library(): a library added without a place here stops the configuration.
set(omninav_link_order config evaluation report navigation lattice memory signature compass io omni sim
                       measures core)
get_property(omninav_libraries GLOBAL PROPERTY OMNINAV_LIBRARIES)
foreach(library IN LISTS omninav_libraries)
  if(NOT library IN_LIST omninav_link_order)
    message(FATAL_ERROR "cmake/install.cmake: give omninav_${library} its place in "
                        "omninav_link_order (omninav.pc links the libraries in that order)")
  endif()
endforeach()
list(TRANSFORM omninav_link_order PREPEND "-lomninav_" OUTPUT_VARIABLE OMNINAV_PC_LIBS)
list(JOIN OMNINAV_PC_LIBS " " OMNINAV_PC_LIBS)
# Debian's Ceres is a static library: the libraries it uses follow it (CeresTargets.cmake's
# INTERFACE_LINK_LIBRARIES; SuiteSparse and BLAS/LAPACK through their Debian names).
set(OMNINAV_PC_CERES "-lceres -lglog -lgflags -lspqr -lcholmod -lamd -lcamd -lccolamd -lcolamd \
-lsuitesparseconfig -lcxsparse -llapack -lblas -lf77blas -latlas")
# ROS 1's libraries, which omninav_io links (libs/io/CMakeLists.txt), have no pkg-config files.
list(TRANSFORM OMNINAV_ROS1_LIBRARY_NAMES PREPEND "-l" OUTPUT_VARIABLE OMNINAV_PC_ROS1)
list(JOIN OMNINAV_PC_ROS1 " " OMNINAV_PC_ROS1)
# Relocatable: the prefix is found from where the file lies (pkg-config's pcfiledir), so that
# `cmake --install --prefix P` may choose any P.
file(RELATIVE_PATH OMNINAV_PC_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" OMNINAV_PC_PREFIX "${OMNINAV_PC_PREFIX}")
configure_file(cmake/omninav.pc.in ${CMAKE_CURRENT_BINARY_DIR}/omninav.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/omninav.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

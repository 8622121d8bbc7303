# The installed C++ package (issue 16): `cmake --install` puts the libraries, their public headers and
# cudahullConfig.cmake under the prefix, so that find_package(cudahull) gives cudahull::cudahull (the
# one-call API, with the Engine and everything below it).  The file readers (io/), the viewer and Qhull's
# bench are not part of it.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CUDAHULL_PACKAGE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/cudahull")

# cuda/include is a source path that an installed target cannot carry; the package installs no CUDA header
# (make_backend() in convex_hull.hpp stands for them), so that path holds in the build tree only.
set_property(TARGET cudahull_cuda PROPERTY INTERFACE_INCLUDE_DIRECTORIES
                                           "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/cuda/include>")

install(TARGETS cudahull_api cudahull_engine cudahull_resident cudahull_cuda cudahull_reference cudahull_parallel cudahull_core
        EXPORT cudahullTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT library)
foreach(folder core parallel reference engine engine/resident api)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${folder}/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
          COMPONENT library)
endforeach()
install(EXPORT cudahullTargets NAMESPACE cudahull:: DESTINATION "${CUDAHULL_PACKAGE_DIR}" COMPONENT library)

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/cudahullConfig.cmake.in"
                              "${CMAKE_CURRENT_BINARY_DIR}/cudahullConfig.cmake"
                              INSTALL_DESTINATION "${CUDAHULL_PACKAGE_DIR}")
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/cudahullConfigVersion.cmake"
                                 VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/cudahullConfig.cmake"
              "${CMAKE_CURRENT_BINARY_DIR}/cudahullConfigVersion.cmake"
        DESTINATION "${CUDAHULL_PACKAGE_DIR}" COMPONENT library)

# `cmake --install build [--prefix DIR]`: the program (bin/pounding), the library
# (lib/libpounding.a), its headers (include/pounding/) and a CMake package, so that another project
# writes find_package(pounding) and links pounding::pounding (tests/install/ builds such a
# consumer). The library is static; the package finds what it links (Debian's -dev packages).
include(CMakePackageConfigHelpers)

set(POUNDING_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pounding)
install(TARGETS pounding_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS pounding EXPORT poundingTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/pounding DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT poundingTargets NAMESPACE pounding:: DESTINATION ${POUNDING_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/poundingConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/poundingConfig.cmake INSTALL_DESTINATION ${POUNDING_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/poundingConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)  # 0.x: a minor release may break the API
install(FILES ${PROJECT_BINARY_DIR}/poundingConfig.cmake ${PROJECT_BINARY_DIR}/poundingConfigVersion.cmake
        DESTINATION ${POUNDING_CMAKE_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/NOTICE
        DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)

# Install rules (docs/install.md): `cmake --install BUILD --prefix P` puts the
# tool, libunstack.so, its modules, the headers, the man page, unstack.pc
# and the CMake package under P in Debian's layout. Every path is relative
# to P, so the prefix can be chosen at install time; the target
# us_installed builds exactly what is installed (`make install`).
include(CMakePackageConfigHelpers)
set(us_pkgdir ${CMAKE_INSTALL_LIBDIR}/cmake/unstack)

# the tool and the shared library (libunstack.so.0.1.0, its SONAME link
# libunstack.so.0 and the namelink libunstack.so); no RPATH: the library
# directory is the loader's own under /usr and /usr/local
set_target_properties(unstack_shared PROPERTIES EXPORT_NAME unstack)
install(TARGETS unstack_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS unstack_shared EXPORT unstackTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})

# the modules (every us_module target), where src/core/module.c looks for
# them: LIBDIR/unstack, seen from BINDIR and from LIBDIR
get_property(us_all_targets DIRECTORY ${CMAKE_SOURCE_DIR} PROPERTY BUILDSYSTEM_TARGETS)
list(FILTER us_all_targets INCLUDE REGEX "^us_mod_")
install(TARGETS ${us_all_targets} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/unstack)

# the public headers and the man page
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/unstack DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${CMAKE_SOURCE_DIR}/docs/unstack.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

# the CMake package: find_package(unstack) gives unstack::unstack
install(EXPORT unstackTargets NAMESPACE unstack:: DESTINATION ${us_pkgdir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/unstackConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_SOURCE_DIR}/cmake/unstackConfig.cmake
              ${CMAKE_BINARY_DIR}/unstackConfigVersion.cmake DESTINATION ${us_pkgdir})

# unstack.pc: its prefix is the one given at install time, so the template
# keeps @prefix@ until then (written per prefix, for installs side by side)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(US_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
  set(us_pc_dest "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
else()
  set(US_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(us_pc_dest "@prefix@/${CMAKE_INSTALL_LIBDIR}/pkgconfig")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(US_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(US_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
set(US_PC_PREFIX "@prefix@")
configure_file(${CMAKE_SOURCE_DIR}/cmake/unstack.pc.in ${CMAKE_BINARY_DIR}/unstack.pc.in @ONLY)
install(CODE "set(us_pc_in [[${CMAKE_BINARY_DIR}/unstack.pc.in]])\nset(us_pc_dest [[${us_pc_dest}]])")
install(CODE [[
  string(MD5 us_pc_key "${CMAKE_INSTALL_PREFIX}")
  set(us_pc_out "${us_pc_in}.d/${us_pc_key}/unstack.pc")
  file(READ "${us_pc_in}" us_pc)
  string(REPLACE "@prefix@" "${CMAKE_INSTALL_PREFIX}" us_pc "${us_pc}")
  string(REPLACE "@prefix@" "${CMAKE_INSTALL_PREFIX}" us_pc_dest "${us_pc_dest}")
  file(WRITE "${us_pc_out}" "${us_pc}")
  file(INSTALL DESTINATION "${us_pc_dest}" TYPE FILE FILES "${us_pc_out}")
]])

# what `make install` builds: the installed targets only, no tests
add_custom_target(us_installed)
add_dependencies(us_installed unstack_cli unstack_shared ${us_all_targets})

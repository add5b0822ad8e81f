# `cmake --install` and the Debian package (`cpack -G DEB` in the build directory): the binary, the
# tools rcdem runs (plots, study report), the examples (the built-in studies' scenarios), the
# documentation and a man page made from `rcdem --help` by help2man (Debian's help2man; without
# it, no man page). The binary finds its tools and examples beside it, in PREFIX/share/rcdem.
include(GNUInstallDirs)
install(TARGETS rcdem RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/tools/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rcdem/tools
        FILES_MATCHING PATTERN "*.py")
install(DIRECTORY ${CMAKE_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rcdem/examples)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The documents and their figures and tables, not the archived study runs (tens of MB).
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}
        FILES_MATCHING PATTERN "*.md" PATTERN "*.png" PATTERN "*.csv" PATTERN "*.json")

find_program(RCDEM_HELP2MAN help2man)
if(RCDEM_HELP2MAN)
  set(RCDEM_MAN_PAGE ${CMAKE_BINARY_DIR}/rcdem.1)
  set(RCDEM_MAN_COMMANDS ${CMAKE_BINARY_DIR}/rcdem_commands.h2m)
  add_custom_command(
    OUTPUT ${RCDEM_MAN_PAGE}
    COMMAND ${CMAKE_COMMAND} -DRCDEM=$<TARGET_FILE:rcdem> -DOUT=${RCDEM_MAN_COMMANDS}
            -P ${CMAKE_SOURCE_DIR}/cmake/man_commands.cmake
    COMMAND ${RCDEM_HELP2MAN} --no-info --section 1
            --name "3D rigid-particle model for reinforced-concrete fracture"
            --include ${RCDEM_MAN_COMMANDS} --output ${RCDEM_MAN_PAGE} $<TARGET_FILE:rcdem>
    DEPENDS rcdem ${CMAKE_SOURCE_DIR}/cmake/man_commands.cmake
    COMMENT "Man page from rcdem --help and each command's --help")
  add_custom_target(rcdem_man ALL DEPENDS ${RCDEM_MAN_PAGE})
  install(FILES ${RCDEM_MAN_PAGE} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rcdem)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "rcdem developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "3D rigid-particle (VGCM-3D) model for reinforced-concrete fracture")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries' packages from dpkg-shlibdeps; the tools' Python packages by name.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy, python3-matplotlib")
include(CPack)

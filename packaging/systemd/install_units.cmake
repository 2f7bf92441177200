# Run by `cmake --install` and by CPack (cmake/Packaging.cmake) at install time, when the prefix is
# known: writes the systemd units with the installed programs' and the node config's absolute paths.
# In: CMAKE_INSTALL_PREFIX (/usr for the package), CUPOLA_INSTALL_BINDIR, CUPOLA_INSTALL_DATADIR,
# CUPOLA_INSTALL_SYSCONFDIR and CUPOLA_UNIT_SOURCE_DIR (this folder).
set(CUPOLA_BINDIR "${CMAKE_INSTALL_PREFIX}/${CUPOLA_INSTALL_BINDIR}")
set(CUPOLA_DOCDIR "${CMAKE_INSTALL_PREFIX}/${CUPOLA_INSTALL_DATADIR}/doc/cupola")
# GNUInstallDirs' rule for the configuration folder: /etc for the /usr prefix, else under the prefix.
if(IS_ABSOLUTE "${CUPOLA_INSTALL_SYSCONFDIR}")
  set(CUPOLA_SYSCONFDIR "${CUPOLA_INSTALL_SYSCONFDIR}")
elseif(CMAKE_INSTALL_PREFIX STREQUAL "/usr" OR CMAKE_INSTALL_PREFIX STREQUAL "/")
  set(CUPOLA_SYSCONFDIR "/${CUPOLA_INSTALL_SYSCONFDIR}")
else()
  set(CUPOLA_SYSCONFDIR "${CMAKE_INSTALL_PREFIX}/${CUPOLA_INSTALL_SYSCONFDIR}")
endif()
set(unit_dir "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/lib/systemd/system")
foreach(unit cupola-slave@.service cupola-master.service)
  message(STATUS "Installing: ${unit_dir}/${unit}")
  configure_file("${CUPOLA_UNIT_SOURCE_DIR}/${unit}.in" "${unit_dir}/${unit}" @ONLY)
  file(CHMOD "${unit_dir}/${unit}" PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
  list(APPEND CMAKE_INSTALL_MANIFEST_FILES "${unit_dir}/${unit}")
endforeach()

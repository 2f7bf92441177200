# Install rules (`cmake --install build`) and the Debian package (`cpack` in the build folder,
# CPack's DEB generator). Included by the root CMakeLists.txt after master/, slave/ and tools/.
# What goes where (docs/DEPLOYMENT.md):
#   bin/cupola-*                          every program target named cupola-* (see below)
#   share/cupola/data/                    data/ (the programs find it through common/util/data_files.hpp)
#   share/cupola/configs/                 the example configs of configs/ (they reach ../../data/ as in the tree)
#   share/cupola/node/cluster.json        a render node's config to copy to /etc/cupola/ (packaging/node/)
#   lib/systemd/system/                   cupola-slave@.service, cupola-master.service (packaging/systemd/)
#   lib/sysusers.d/cupola.conf            the system user `cupola` and its groups (packaging/sysusers.d/)
#   lib/udev/rules.d/                     configs/udev/70-cupola-navigation.rules
# The node's own files (/etc/cupola/cluster.json, its key) are the operator's, never the package's.
include(GNUInstallDirs)
# `cmake --install` and `cpack` take the programs as built and build nothing themselves (else
# cpack, and the ctest packaging_deb that runs it, would build every test and benchmark first):
# build first, `cmake --build build`, then install or package.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

# Programs: every executable target whose name starts with cupola- that is declared in master/,
# slave/ or tools/ (or a folder below them) is installed. A new program (cupola-warp,
# cupola-mpcdi-gen...) is picked up by its add_executable() alone; tests/test_packaging.sh checks
# that every build/bin/cupola-* is in the package.
function(cupola_collect_programs dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  set(found "")
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    if(type STREQUAL "EXECUTABLE" AND t MATCHES "^cupola-")
      list(APPEND found ${t})
    endif()
  endforeach()
  foreach(d ${subdirs})
    cupola_collect_programs(${d} below)
    list(APPEND found ${below})
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

set(CUPOLA_PROGRAMS "")
foreach(dir master slave tools)
  cupola_collect_programs(${CMAKE_SOURCE_DIR}/${dir} programs)
  list(APPEND CUPOLA_PROGRAMS ${programs})
endforeach()
install(TARGETS ${CUPOLA_PROGRAMS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Run-time data. The installed programs look for it relative to their own folder, so one build
# serves `cmake --install --prefix ANY` and the package's /usr alike (common/util/data_files.cpp).
file(RELATIVE_PATH CUPOLA_BIN_TO_DATA ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_DATADIR}/cupola)
set_source_files_properties(${CMAKE_SOURCE_DIR}/common/util/data_files.cpp TARGET_DIRECTORY cupola_common
                            PROPERTIES COMPILE_DEFINITIONS "CUPOLA_BIN_TO_DATA=\"${CUPOLA_BIN_TO_DATA}\"")
install(DIRECTORY ${CMAKE_SOURCE_DIR}/data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/cupola/data)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/cupola/configs
        PATTERN udev EXCLUDE PATTERN "*.cmake" EXCLUDE)
install(FILES ${CMAKE_SOURCE_DIR}/packaging/node/cluster.json DESTINATION ${CMAKE_INSTALL_DATADIR}/cupola/node)
install(FILES ${CMAKE_SOURCE_DIR}/docs/DEPLOYMENT.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/cupola)

# System integration. Not CMAKE_INSTALL_LIBDIR: systemd, sysusers and udev read lib/ under the
# prefix (/usr/lib/..., or /usr/local/lib/... for a local install), never the multiarch folder.
install(FILES ${CMAKE_SOURCE_DIR}/packaging/sysusers.d/cupola.conf DESTINATION lib/sysusers.d)
install(FILES ${CMAKE_SOURCE_DIR}/configs/udev/70-cupola-navigation.rules DESTINATION lib/udev/rules.d)
# The units name the programs' and the node config's absolute paths, which depend on the prefix
# given at install time (CPack installs with /usr, `cmake --install --prefix P` with P): they are
# written then, by packaging/systemd/install_units.cmake.
install(CODE "set(CUPOLA_UNIT_SOURCE_DIR \"${CMAKE_SOURCE_DIR}/packaging/systemd\")
set(CUPOLA_INSTALL_BINDIR \"${CMAKE_INSTALL_BINDIR}\")
set(CUPOLA_INSTALL_DATADIR \"${CMAKE_INSTALL_DATADIR}\")
set(CUPOLA_INSTALL_SYSCONFDIR \"${CMAKE_INSTALL_SYSCONFDIR}\")")
install(SCRIPT ${CMAKE_SOURCE_DIR}/packaging/systemd/install_units.cmake)

# The Debian package: `cd build && cpack` writes cupola_<version>_<arch>.deb.
set(CUPOLA_PACKAGE_MAINTAINER "Cupola developers <cupola@localhost>"
    CACHE STRING "Maintainer field of the .deb (name <email>)")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME cupola)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "Cupola")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "multi-channel dome and cluster renderer (master, render nodes, tools)")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "Cupola renders one sky on many machines at once, one render node per projector channel.
A master broadcasts an authenticated state snapshot per frame over UDP and runs a frame
barrier; each render node (cupola-slave) draws its channel headlessly through EGL.
Includes systemd units (cupola-slave@CHANNEL.service, cupola-master.service), the
system user cupola, a udev rule for navigation devices, example configs and data.")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${CUPOLA_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Depends: the shared libraries' packages, found by dpkg-shlibdeps, plus what is loaded at run
# time and so invisible to it: Mesa's EGL vendor library and its drivers (llvmpipe on machines
# without a GPU; libglvnd picks a GPU vendor's library where one is installed), and what the
# maintainer scripts use to create the user (systemd-sysusers, else adduser).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl-mesa0, libgl1-mesa-dri, systemd | adduser")
# The example scenes texture the Earth with xplanet's image and the planets with OpenUniverse's maps;
# oiiotool reads the frames' metadata.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "xplanet-images, openuniverse-common")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "openimageio-tools")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_SOURCE_DIR}/packaging/debian/postinst
                                       ${CMAKE_SOURCE_DIR}/packaging/debian/prerm ${CMAKE_SOURCE_DIR}/packaging/debian/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# Release binaries without their debug sections (RelWithDebInfo's are several times larger).
set(CPACK_STRIP_FILES ON)
include(CPack)

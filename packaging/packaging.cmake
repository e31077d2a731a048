# Installing palprig (cmake --install) and its Debian package (CPack, `make package`): included
# last from the top CMakeLists.txt. What goes where, under the install prefix (/usr in the package):
#   bin/palprig                                  the program
#   share/palprig/{protocols,scenes,rigs,...}    the shipped data, found by name (cli/data_files.hpp)
#   share/man/man1/palprig*.1.gz                 man pages generated from --help (cli_docs.py)
#   share/bash-completion/completions/palprig    bash completion, generated likewise
#   share/applications/palprig.desktop, share/icons/hicolor/scalable/apps/palprig.svg
#   share/doc/palprig/{copyright,changelog.gz,README.md,CITATION.cff}
#   lib/sysusers.d/palprig.conf                  the palprig group
#   lib/udev/rules.d/70-palprig.rules            comedi cards and pen tablets for that group
#   /etc/security/limits.d/palprig.conf          real-time priority and locked memory for it
# The package's postinst creates the group (systemd-sysusers, else addgroup) and reloads udev.
include(GNUInstallDirs)

# The maintainer a lab names when it builds the package for its PCs (lintian wants a real address).
set(PALPRIG_PACKAGE_MAINTAINER "The palprig developers <palprig@example.org>" CACHE STRING
  "Maintainer field of the Debian package: who to write to about this build of it")
set(PALPRIG_GIT_COMMIT "" CACHE STRING "The commit palprig --version names when the source is not a git clone")
# `make package` and `cmake --install` do not build everything first (the suites, benchmarks and
# fuzz targets are not installed); the Makefile builds the installed targets before CPack.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)

install(TARGETS palprig RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/palprig
  PATTERN "make_*.py" EXCLUDE)

# Man pages and completion from the built program's own --help (a window-less run of it).
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(_docs ${CMAKE_BINARY_DIR}/packaging)
# (Leak checking off: in a sanitizer build, a leak report at exit would fail the build over --help.)
add_custom_command(OUTPUT ${_docs}/man1/palprig.1.gz ${_docs}/completion/palprig
  COMMAND ${CMAKE_COMMAND} -E env QT_QPA_PLATFORM=offscreen ASAN_OPTIONS=detect_leaks=0
    ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/packaging/cli_docs.py --palprig $<TARGET_FILE:palprig>
    --man-dir ${_docs}/man1 --completion ${_docs}/completion/palprig
  DEPENDS palprig ${PROJECT_SOURCE_DIR}/packaging/cli_docs.py
  COMMENT "palprig: man pages and bash completion from --help")
# Part of every build but the sanitizer ones (nobody installs those; make package builds it anyway).
if(PALPRIG_SANITIZE OR PALPRIG_TSAN)
  set(_cli_docs_all)
else()
  set(_cli_docs_all ALL)
endif()
add_custom_target(palprig_cli_docs ${_cli_docs_all} DEPENDS ${_docs}/man1/palprig.1.gz ${_docs}/completion/palprig)
install(DIRECTORY ${_docs}/man1 DESTINATION ${CMAKE_INSTALL_MANDIR} FILES_MATCHING PATTERN "*.1.gz")
install(FILES ${_docs}/completion/palprig DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)

install(FILES ${PROJECT_SOURCE_DIR}/packaging/palprig.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/palprig.svg
  DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)

# Debian's copyright file and a gzipped changelog; the README and the citation beside them.
set(_doc_dir ${CMAKE_INSTALL_DATADIR}/doc/palprig)
file(READ ${PROJECT_SOURCE_DIR}/LICENSE _license)
string(REGEX REPLACE "\n\n" "\n.\n" _license_debian "${_license}")
string(REGEX REPLACE "\n([^\n])" "\n \\1" _license_debian "${_license_debian}")
file(WRITE ${_docs}/copyright
  "Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/\n"
  "Upstream-Name: palprig\n\nFiles: *\nCopyright: 2026 The palprig developers\nLicense: MIT\n"
  " ${_license_debian}")
add_custom_command(OUTPUT ${_docs}/changelog.gz
  COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/CHANGELOG.md > ${_docs}/changelog.gz
  DEPENDS ${PROJECT_SOURCE_DIR}/CHANGELOG.md)
# The package's own changelog in Debian's format (the package revision is 1: the upstream
# changelog above is CHANGELOG.md); dated when the build was configured, or SOURCE_DATE_EPOCH.
set(PALPRIG_DEBIAN_REVISION 1)
string(TIMESTAMP _debian_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE ${_docs}/changelog.Debian
  "palprig (${PROJECT_VERSION}-${PALPRIG_DEBIAN_REVISION}) unstable; urgency=medium\n\n"
  "  * Built with CPack from the palprig sources (make package); what changed is in\n"
  "    /usr/share/doc/palprig/changelog.gz (CHANGELOG.md).\n\n"
  " -- ${PALPRIG_PACKAGE_MAINTAINER}  ${_debian_date}\n")
add_custom_command(OUTPUT ${_docs}/changelog.Debian.gz
  COMMAND gzip -9nc ${_docs}/changelog.Debian > ${_docs}/changelog.Debian.gz
  DEPENDS ${_docs}/changelog.Debian)
add_custom_target(palprig_changelog ALL DEPENDS ${_docs}/changelog.gz ${_docs}/changelog.Debian.gz)
install(FILES ${_docs}/copyright ${_docs}/changelog.gz ${_docs}/changelog.Debian.gz ${PROJECT_SOURCE_DIR}/README.md
  ${PROJECT_SOURCE_DIR}/CITATION.cff DESTINATION ${_doc_dir})

# Running as a lab user, not root (docs/rig-pc.md).
install(FILES ${PROJECT_SOURCE_DIR}/packaging/palprig.sysusers DESTINATION lib/sysusers.d RENAME palprig.conf)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/70-palprig.rules DESTINATION lib/udev/rules.d)
# pam_limits reads only /etc/security/limits.d, whatever the prefix.
install(FILES ${PROJECT_SOURCE_DIR}/packaging/palprig-limits.conf DESTINATION /etc/security/limits.d
  RENAME palprig.conf)

# The Debian package: palprig_VERSION_ARCH.deb in the build folder.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME palprig)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${PALPRIG_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "pneumatic multi-finger palpation rig and its studies")
# The long description (CPack puts the summary above it and indents each line).
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "palprig drives a pneumatic multi-finger palpation rig (three finger actuators
fed by proportional pressure regulators over Modbus TCP or a comedi DAQ card)
from a pen tablet or a tracker, renders stiffness maps, function-based tissue
and arterial pulses under the fingers, and runs stiffness-discrimination,
tumor-localisation, threshold and pulse-localisation studies with their
statistics and exports. Everything also runs on a simulated rig.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_PACKAGE_RELEASE ${PALPRIG_DEBIAN_REVISION})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # palprig_VERSION-REVISION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Dependencies from the binary's own libraries (dpkg-shlibdeps), plus what postinst calls.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
set(CPACK_STRIP_FILES TRUE)
file(WRITE ${_docs}/conffiles "/etc/security/limits.d/palprig.conf\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/postinst
  ${PROJECT_SOURCE_DIR}/packaging/postrm ${_docs}/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
include(CPack)

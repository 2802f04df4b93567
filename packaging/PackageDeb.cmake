# CPack's DEB generator: pvtap_<version>[~<release tag>]_<arch>.deb (scripts/package runs it on a
# clean build, with the tag of the Debian release it runs on).

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pvtap)
set(CPACK_PACKAGE_VERSION ${PVTAP_PACKAGE_VERSION})
set(CPACK_PACKAGE_CONTACT "${PVTAP_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
# The extended description, wrapped at 80 columns as Debian wants it (CPack does not wrap).
string(JOIN "\n" CPACK_PACKAGE_DESCRIPTION
  "pvtap shows what crosses the wire between a data logger and its solar"
  "inverters on an RS485 bus: which station was asked for what, what it answered,"
  "which frames were damaged and which requests went unanswered. It knows the"
  "ASCII (Korean inverter protocol), Hybrid V2.2 and GSL (Modbus RTU) dialects."
  "."
  "This package holds the pvtap program (pvtap audit for captures, pvtap sniff"
  "for live RS485 taps and gateway traffic), its Wireshark plugin, the RS485 tap"
  "capture interface for Wireshark, register maps and sample captures.")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION electronics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)

# Everything under /usr; the absolute destinations (Wireshark's plugin and extcap folders)
# are staged through DESTDIR like the rest, never written to the build machine's /usr.
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_SET_DESTDIR ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS
    OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)

# Library dependencies come from dpkg-shlibdeps. On top of them, the plugin loads only into
# the Wireshark release series it was built for: the package of that libwireshark ABI (its
# SONAME, libwireshark.so.16 -> libwireshark16 for 4.0), within that series, so that an
# upgrade of Wireshark to another series is refused instead of crashing.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(TARGET epan)
  get_target_property(pvtap_epan_soname epan IMPORTED_SONAME_NONE)
  if(NOT pvtap_epan_soname)
    get_target_property(pvtap_epan_soname epan IMPORTED_SONAME_RELEASE)
  endif()
  string(REGEX REPLACE "^libwireshark\\.so\\.([0-9]+)$" "libwireshark\\1" PVTAP_WIRESHARK_ABI_PACKAGE
         "${pvtap_epan_soname}")
  if(NOT PVTAP_WIRESHARK_ABI_PACKAGE MATCHES "^libwireshark[0-9]+$")
    message(FATAL_ERROR "pvtap: cannot tell libwireshark's ABI from its SONAME '${pvtap_epan_soname}'")
  endif()
  math(EXPR pvtap_next_minor "${Wireshark_MINOR_VERSION} + 1")
  set(pvtap_series "${Wireshark_MAJOR_VERSION}.${Wireshark_MINOR_VERSION}")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "${PVTAP_WIRESHARK_ABI_PACKAGE} (>= ${pvtap_series}), ${PVTAP_WIRESHARK_ABI_PACKAGE} (<< ${Wireshark_MAJOR_VERSION}.${pvtap_next_minor}~)")
  set(pvtap_recommends "wireshark | tshark, ")
endif()
# libsigrok is loaded only to read a logic recording (dlopen), so dpkg-shlibdeps does not see
# it: recommended, under its name before and after Debian's 64-bit time transition.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "${pvtap_recommends}libsigrok4 | libsigrok4t64")

include(CPack)

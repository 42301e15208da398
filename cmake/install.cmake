# `cmake --install build [--prefix /opt/ldvnav]` (issue 53): every file the units and the configs name, where they
# name it.
#   PREFIX/bin                    the services and ldv
#   PREFIX/share/deploy, .../services/<name>   the docs the units' Documentation= lines point at
#   LDV_SYSTEMD_UNIT_DIR          the units, their /opt/ldvnav replaced by the install prefix and /etc/ldvnav by
#                                 LDV_SYSCONF_DIR (at install time: `--prefix` given then is the one that counts)
#   LDV_SYSCONF_DIR               the service configs, the vehicle's kfgins.yaml template and rtkrcv.conf; a config
#                                 already there that differs is kept and the new default written beside it as .dist
#   LDV_SYSCTL_DIR                the sysctl file (network buffers for the bus)
# Absolute destinations honour DESTDIR (packaging, the install test).
set(LDV_SYSTEMD_UNIT_DIR "/lib/systemd/system" CACHE PATH "where the systemd units are installed")
set(LDV_SYSCONF_DIR "/etc/ldvnav" CACHE PATH "where the service configurations are installed")
set(LDV_SYSCTL_DIR "/etc/sysctl.d" CACHE PATH "where the sysctl file is installed")

install(TARGETS ldv fusion imu_acq gnss_link tspi_pub ldv_logger RUNTIME DESTINATION bin)
install(FILES deploy/README.md DESTINATION share/deploy)
install(FILES deploy/rtklib/rtkrcv_instantaneous_ar.conf DESTINATION share/deploy/rtklib)
foreach(service fusion gnss_link imu_acq tspi_pub)
  install(FILES services/${service}/README.md DESTINATION share/services/${service})
endforeach()
install(FILES deploy/sysctl/90-ldvnav.conf DESTINATION ${LDV_SYSCTL_DIR})

# A text file with the deployment's paths put in, written at install time.
function(ldv_install_with_paths source destination keep_changed)
  set(keep "")
  if(keep_changed)
    set(keep "
    if(EXISTS \"\${dest}\")
      file(READ \"\${dest}\" installed)
      if(NOT installed STREQUAL text)
        message(STATUS \"Kept (changed): \${dest}; the new default: \${dest}.dist\")
        set(dest \"\${dest}.dist\")
      endif()
    endif()")
  endif()
  install(CODE "
    file(READ \"${source}\" text)
    string(REPLACE \"/opt/ldvnav\" \"\${CMAKE_INSTALL_PREFIX}\" text \"\${text}\")
    string(REPLACE \"/etc/ldvnav\" \"${LDV_SYSCONF_DIR}\" text \"\${text}\")
    set(dest \"\$ENV{DESTDIR}${destination}\")${keep}
    message(STATUS \"Installing: \${dest}\")
    file(WRITE \"\${dest}\" \"\${text}\")
  ")
endfunction()

file(GLOB LDV_UNITS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/deploy/systemd/*.service ${CMAKE_SOURCE_DIR}/deploy/systemd/*.target)
foreach(unit ${LDV_UNITS})
  get_filename_component(name ${unit} NAME)
  ldv_install_with_paths(${unit} ${LDV_SYSTEMD_UNIT_DIR}/${name} FALSE)
endforeach()
file(GLOB LDV_CONFIGS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/deploy/config/*.yaml)
foreach(config ${LDV_CONFIGS})
  get_filename_component(name ${config} NAME)
  ldv_install_with_paths(${config} ${LDV_SYSCONF_DIR}/${name} TRUE)
endforeach()
ldv_install_with_paths(${CMAKE_SOURCE_DIR}/deploy/rtklib/rtkrcv_instantaneous_ar.conf ${LDV_SYSCONF_DIR}/rtkrcv.conf TRUE)

# A Debian package of the same layout (`cpack -G DEB` in the build folder, or scripts/package_deb.sh): dependencies
# from what the binaries link (dpkg-shlibdeps), every file under /etc/ldvnav a conffile (dpkg keeps a changed one),
# maintainer scripts that reload systemd and enable nothing.
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "ldvnav")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_CONTACT "ldvnav developers <ldvnav@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time GPS/INS navigation (TSPI) with its IMU error-model toolbox")
set(CPACK_PACKAGING_INSTALL_PREFIX "/opt/ldvnav")
set(CPACK_INSTALL_PREFIX "/opt/ldvnav")  # the prefix the install step sees (CPACK_SET_DESTDIR)
set(CPACK_SET_DESTDIR ON)  # the absolute destinations (units, /etc/ldvnav) land in the package's root
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "rtklib, iproute2")
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
file(GLOB LDV_CONFFILE_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/deploy/config/*.yaml)
set(LDV_CONFFILES "")
foreach(config ${LDV_CONFFILE_SOURCES})
  get_filename_component(name ${config} NAME)
  string(APPEND LDV_CONFFILES "${LDV_SYSCONF_DIR}/${name}\n")
endforeach()
string(APPEND LDV_CONFFILES "${LDV_SYSCONF_DIR}/rtkrcv.conf\n${LDV_SYSCTL_DIR}/90-ldvnav.conf\n")
file(WRITE ${CMAKE_BINARY_DIR}/debian/conffiles "${LDV_CONFFILES}")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${CMAKE_BINARY_DIR}/debian/conffiles ${CMAKE_SOURCE_DIR}/deploy/debian/postinst ${CMAKE_SOURCE_DIR}/deploy/debian/postrm)
include(CPack)

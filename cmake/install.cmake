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

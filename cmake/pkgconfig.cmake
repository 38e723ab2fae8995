# pkgconfig.cmake — install rule for shapedem.pc (template cmake/shapedem.pc.in).
#
# The file must name the prefix the library is installed into, which is the
# one given to `cmake --install --prefix DIR` and may differ from
# CMAKE_INSTALL_PREFIX at configure time. So everything known now (version,
# directories, private dependencies) is filled in at configure time and the
# prefix at install time, by install(CODE) writing straight into the prefix.

# Directories relative to ${prefix} unless the user gave absolute ones.
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(SD_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(SD_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()

# What libshapedem.a needs: libyaml through its own .pc when it was found
# that way, libm, and the OpenMP runtime through the compiler's flag.
set(SD_PC_REQUIRES_PRIVATE "")
set(SD_PC_LIBS_PRIVATE "")
if(YAML_FOUND)
  set(SD_PC_REQUIRES_PRIVATE "yaml-0.1")
else()
  string(APPEND SD_PC_LIBS_PRIVATE "${YAML_LIBRARIES} ")
endif()
# HDF5 (checkpoints): the module pkg-config found it by (hdf5-serial on
# Debian, whose plain hdf5.pc may point at the MPI build: CMakeLists.txt)
if(SD_HDF5_FOUND)
  string(APPEND SD_PC_REQUIRES_PRIVATE " ${SD_HDF5_PC}")
else()
  foreach(lib ${SD_HDF5_LINK_LIBRARIES})
    string(APPEND SD_PC_LIBS_PRIVATE "${lib} ")
  endforeach()
endif()
string(APPEND SD_PC_LIBS_PRIVATE "-lm")
if(SHAPEDEM_OPENMP)
  string(APPEND SD_PC_LIBS_PRIVATE " ${OpenMP_C_FLAGS}")
endif()

# A sanitizer build's library needs the sanitizer runtimes in the program,
# loaded first.
set(SD_PC_SANITIZE "")
if(SHAPEDEM_SANITIZE)
  set(SD_PC_SANITIZE " -fsanitize=address,undefined")
endif()

set(SD_PC_PREFIX "@SD_PC_PREFIX@") # left for the install step
configure_file(${PROJECT_SOURCE_DIR}/cmake/shapedem.pc.in
  ${PROJECT_BINARY_DIR}/shapedem.pc.in @ONLY)

if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(SD_PC_DEST "\$ENV{DESTDIR}${CMAKE_INSTALL_LIBDIR}/pkgconfig")
else()
  set(SD_PC_DEST "\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig")
endif()
install(CODE "
  set(SD_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  file(READ \"${PROJECT_BINARY_DIR}/shapedem.pc.in\" sd_pc)
  string(CONFIGURE \"\${sd_pc}\" sd_pc @ONLY)
  message(STATUS \"Installing: ${SD_PC_DEST}/shapedem.pc\")
  file(WRITE \"${SD_PC_DEST}/shapedem.pc\" \"\${sd_pc}\")
  list(APPEND CMAKE_INSTALL_MANIFEST_FILES \"${SD_PC_DEST}/shapedem.pc\")
")

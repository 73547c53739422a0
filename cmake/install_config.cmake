# Installs the example configuration the way dpkg treats a conffile: a file that is not there
# yet is installed; one that is already there is left as it is, since an operator may have
# edited it, and the new example goes beside it as FILE.new when the two differ.
# Run by `cmake --install` with EIP2MQTT_CONFIG_FILES (source paths) and EIP2MQTT_CONFIG_DEST
# (the destination directory: absolute, or relative to the install prefix) set.

if(IS_ABSOLUTE "${EIP2MQTT_CONFIG_DEST}")
  set(destination "${EIP2MQTT_CONFIG_DEST}")
else()
  set(destination "${CMAKE_INSTALL_PREFIX}/${EIP2MQTT_CONFIG_DEST}")
endif()
# file(INSTALL) puts DESTDIR in front of its destination itself; the checks must too.
set(staged "$ENV{DESTDIR}${destination}")

foreach(source IN LISTS EIP2MQTT_CONFIG_FILES)
  get_filename_component(name "${source}" NAME)
  if(NOT EXISTS "${staged}/${name}")
    file(INSTALL "${source}" DESTINATION "${destination}")
    continue()
  endif()
  file(SHA256 "${source}" example_sum)
  file(SHA256 "${staged}/${name}" installed_sum)
  if(example_sum STREQUAL installed_sum)
    message(STATUS "Up-to-date: ${staged}/${name}")
  else()
    message(STATUS "Kept: ${staged}/${name}, which differs from the example; "
      "the example is ${name}.new beside it")
    file(INSTALL "${source}" DESTINATION "${destination}" RENAME "${name}.new")
  endif()
endforeach()

# MeshLab2025Sources.cmake — MeshLab 2025.07's plugin headers (src/common) and vcglib, from the
# orig tarball of Debian's source package meshlab 2025.07~dfsg-4, checked against its SHA-256.
#
#   growth_meshlab2025_sources(<var>)
#
# Sets <var> to a folder holding ML_VERSION, src/common and src/vcglib. In order, it takes:
#   1. MESHLAB2025_DIR, when it already holds them (scripts/setup.sh unpacks them there);
#   2. the tarball named by GROWTH_MESHLAB2025_TARBALL (a CMake or environment variable), or one
#      found in third_party/ or ../shared/third_party/ beside the source tree;
#   3. a download from Debian's archive.
# A tarball is used only when its checksum matches, and is unpacked once into the build tree.
# Nothing of it is ever written into the source tree.

set(GROWTH_MESHLAB2025_ORIG "meshlab_2025.07~dfsg.orig.tar.xz")
set(GROWTH_MESHLAB2025_SHA256 "d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4")
set(GROWTH_MESHLAB2025_URL "https://deb.debian.org/debian/pool/main/m/meshlab/${GROWTH_MESHLAB2025_ORIG}")

function(_growth_has_meshlab2025_sources dir out)
  if(EXISTS "${dir}/ML_VERSION" AND EXISTS "${dir}/src/common/plugins/interfaces/filter_plugin.h"
     AND EXISTS "${dir}/src/vcglib/vcg/complex/complex.h")
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()

function(_growth_sha256_ok file out)
  set(${out} FALSE PARENT_SCOPE)
  if(EXISTS "${file}")
    file(SHA256 "${file}" sum)
    if(sum STREQUAL GROWTH_MESHLAB2025_SHA256)
      set(${out} TRUE PARENT_SCOPE)
    else()
      message(WARNING "MeshLab 2025.07 sources: ${file} has SHA-256 ${sum}, not ${GROWTH_MESHLAB2025_SHA256}; not used")
    endif()
  endif()
endfunction()

function(growth_meshlab2025_sources out)
  if(MESHLAB2025_DIR)
    _growth_has_meshlab2025_sources("${MESHLAB2025_DIR}" have)
    if(have)
      set(${out} "${MESHLAB2025_DIR}" PARENT_SCOPE)
      return()
    endif()
  endif()
  set(unpacked "${PROJECT_BINARY_DIR}/_deps/meshlab-2025.07")
  _growth_has_meshlab2025_sources("${unpacked}" have)
  if(have AND EXISTS "${unpacked}/.sha256")
    file(READ "${unpacked}/.sha256" stamp)
    if(stamp STREQUAL GROWTH_MESHLAB2025_SHA256)
      set(${out} "${unpacked}" PARENT_SCOPE)
      return()
    endif()
  endif()

  set(tarball "")
  set(candidates "")
  if(GROWTH_MESHLAB2025_TARBALL)
    list(APPEND candidates "${GROWTH_MESHLAB2025_TARBALL}")
  elseif(DEFINED ENV{GROWTH_MESHLAB2025_TARBALL})
    list(APPEND candidates "$ENV{GROWTH_MESHLAB2025_TARBALL}")
  endif()
  list(APPEND candidates "${PROJECT_SOURCE_DIR}/third_party/${GROWTH_MESHLAB2025_ORIG}"
                         "${PROJECT_SOURCE_DIR}/../shared/third_party/${GROWTH_MESHLAB2025_ORIG}")
  foreach(c IN LISTS candidates)
    _growth_sha256_ok("${c}" ok)
    if(ok)
      set(tarball "${c}")
      break()
    endif()
  endforeach()
  if(NOT tarball)
    set(tarball "${PROJECT_BINARY_DIR}/_deps/${GROWTH_MESHLAB2025_ORIG}")
    message(STATUS "MeshLab 2025.07 sources: downloading ${GROWTH_MESHLAB2025_URL}")
    file(DOWNLOAD "${GROWTH_MESHLAB2025_URL}" "${tarball}" STATUS status TLS_VERIFY ON
         EXPECTED_HASH SHA256=${GROWTH_MESHLAB2025_SHA256})
    list(GET status 0 code)
    if(NOT code EQUAL 0)
      list(GET status 1 reason)
      file(REMOVE "${tarball}")
      message(FATAL_ERROR "MeshLab 2025.07 sources: cannot download ${GROWTH_MESHLAB2025_URL} (${reason}). "
              "Download ${GROWTH_MESHLAB2025_ORIG} (SHA-256 ${GROWTH_MESHLAB2025_SHA256}) by hand and "
              "set GROWTH_MESHLAB2025_TARBALL to its path.")
    endif()
  endif()

  message(STATUS "MeshLab 2025.07 sources: unpacking src/common and vcglib from ${tarball}")
  set(staging "${PROJECT_BINARY_DIR}/_deps/meshlab-2025.07-staging")
  file(REMOVE_RECURSE "${staging}" "${unpacked}")
  file(MAKE_DIRECTORY "${staging}")
  # Only what a plugin build reads: the version, the plugin API and vcglib.
  file(ARCHIVE_EXTRACT INPUT "${tarball}" DESTINATION "${staging}"
       PATTERNS "*/ML_VERSION" "*/LICENSE.txt" "*/src/common/*" "*/src/vcglib/*")
  file(GLOB top "${staging}/*")
  list(LENGTH top n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "MeshLab 2025.07 sources: unexpected layout of ${tarball}")
  endif()
  file(RENAME "${top}" "${unpacked}")
  file(REMOVE_RECURSE "${staging}")
  file(WRITE "${unpacked}/.sha256" "${GROWTH_MESHLAB2025_SHA256}")
  set(${out} "${unpacked}" PARENT_SCOPE)
endfunction()

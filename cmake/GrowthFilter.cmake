# growth_add_filter(NAME ENGINE): the filter's engine (every .cpp of the current directory's engine/
# folder, whose headers are included by their plain names) as the static library ENGINE, built once
# (no MeshLab type in it), and the MeshLab plugin NAME from the glue NAME.cpp at the folder's top
# (with NAME_layer.h, the engine on layers, through the INTERFACE library NAME_layer), for
# MeshLab 2020.09 into build/plugins/ (with GROWTH_MESHLAB_2020) and, for each precision P (d, f) of GROWTH_2025_PRECISIONS,
# the glue again as NAME_2025P (on growth_meshlab_2025P) for MeshLab 2025.07 into
# ${GROWTH_2025P_DIR}/plugins (build/meshlab-2025.07d/plugins, build/meshlab-2025.07/plugins).
#
# Install components: meshlab-2020.09 (into the installed MeshLab's plugin folder, an absolute path),
# meshlab-2025.07d and meshlab-2025.07 (into PREFIX/lib/meshlab-2025.07d/plugins and
# PREFIX/lib/meshlab-2025.07/plugins), and python (the Python package's growth_meshers/plugins/).
#
# The 2025.07 plugins carry no RUNPATH and name libmeshlab-common and Qt by soname only (linked
# --as-needed), so in PyMeshLab or the GUI they bind to the host's own, already loaded libraries.
function(growth_add_filter name engine)
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/engine/*.cpp")
  add_library(${engine} STATIC ${sources})
  target_include_directories(${engine} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/engine")
  target_link_libraries(${engine} PUBLIC growth PRIVATE growth_warnings)
  set(variants "")
  if(GROWTH_MESHLAB_2020)
    list(APPEND variants "|MeshLab::common|${PROJECT_BINARY_DIR}/plugins")
  endif()
  foreach(p IN LISTS GROWTH_2025_PRECISIONS)
    string(TOUPPER ${p} P)
    list(APPEND variants "_2025${p}|MeshLab2025${p}::common|${GROWTH_2025${P}_DIR}/plugins")
  endforeach()
  foreach(variant IN LISTS variants)
    string(REPLACE "|" ";" parts "${variant}")
    list(GET parts 0 suffix)
    list(GET parts 1 common)
    list(GET parts 2 outdir)
    # The engine on MeshLab layers (NAME_layer.h beside the glue, on growth_meshlab): the glue,
    # tools and tests include it.
    add_library(${name}_layer${suffix} INTERFACE)
    target_include_directories(${name}_layer${suffix} INTERFACE "${CMAKE_CURRENT_SOURCE_DIR}")
    target_link_libraries(${name}_layer${suffix} INTERFACE ${engine} growth_meshlab${suffix})
    if(GROWTH_BUILD_PLUGINS)
      add_library(${name}${suffix} MODULE ${name}.cpp ${name}.h)
      set_target_properties(${name}${suffix} PROPERTIES AUTOMOC ON PREFIX "lib" OUTPUT_NAME ${name}
                            LIBRARY_OUTPUT_DIRECTORY "${outdir}")
      # For 2025.07 the C++ runtime comes first: the wheel's libQt5Core also exports operator
      # delete(void*, size_t), and a plugin bound to that copy would load in no other host.
      set(runtime "")
      if(NOT suffix STREQUAL "")
        set(runtime stdc++)
      endif()
      target_link_libraries(${name}${suffix} PRIVATE ${runtime} ${name}_layer${suffix} ${common} meshlab_compat growth_warnings)
      if(suffix STREQUAL "")
        install(TARGETS ${name} LIBRARY DESTINATION "${MeshLab_PLUGIN_DIR}" COMPONENT meshlab-2020.09)
      else()
        get_filename_component(layout "${outdir}" DIRECTORY)
        get_filename_component(layout "${layout}" NAME) # meshlab-2025.07d or meshlab-2025.07
        set_target_properties(${name}${suffix} PROPERTIES SKIP_BUILD_RPATH ON INSTALL_RPATH "")
        # Every symbol the plugin needs must be in the host's libraries it is linked against.
        target_link_options(${name}${suffix} PRIVATE "LINKER:--as-needed" "LINKER:--no-undefined")
        install(TARGETS ${name}${suffix} LIBRARY DESTINATION "lib/${layout}/plugins"
                COMPONENT ${layout})
        if(GROWTH_PYTHON_PACKAGE)
          install(TARGETS ${name}${suffix} LIBRARY DESTINATION growth_meshers/plugins COMPONENT python)
        endif()
      endif()
    endif()
  endforeach()
endfunction()

# The viewer's script (viewer/src with three.js, bundled by esbuild) compiled into module `target`
# as the definition of kaboum::web::viewerScript() (docs/viewer.md). Needs Node.js and the npm
# packages of viewer/package-lock.json, which scripts/setup.sh installs.
function(kaboum_add_viewer_script target)
  set(viewer_dir ${PROJECT_SOURCE_DIR}/viewer)
  find_program(KABOUM_NODE node)
  if(NOT KABOUM_NODE)
    message(FATAL_ERROR "Node.js (node) not found: the viewer's script is bundled with it at build "
                        "time. Run scripts/setup.sh, which installs it and the viewer's packages.")
  endif()
  foreach(package esbuild three meshoptimizer)
    if(NOT EXISTS ${viewer_dir}/node_modules/${package}/package.json)
      message(FATAL_ERROR "${viewer_dir}/node_modules lacks ${package}: run scripts/setup.sh "
                          "(it runs npm ci in viewer/).")
    endif()
  endforeach()
  file(GLOB viewer_sources CONFIGURE_DEPENDS ${viewer_dir}/src/*.js)
  set(generated ${CMAKE_CURRENT_BINARY_DIR}/viewer_script.cpp)
  add_custom_command(
    OUTPUT ${generated} ${CMAKE_CURRENT_BINARY_DIR}/viewer.js
    COMMAND ${KABOUM_NODE} ${viewer_dir}/build.mjs ${generated}
            ${CMAKE_CURRENT_BINARY_DIR}/viewer.js
    DEPENDS ${viewer_sources} ${viewer_dir}/build.mjs ${viewer_dir}/package-lock.json
    COMMENT "Bundling the viewer's script (esbuild)"
    VERBATIM)
  target_sources(${target} PRIVATE ${generated})
endfunction()

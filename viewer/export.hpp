// The debugger's exports (issue 6, item 6), each written atomically (mesh_io.hpp): the current polyhedron
// as OBJ/OFF/PLY, the trace of every step so far as JSON lines (the `cudahull hull --trace` format), and
// the current step's decision array (Fig. 7) as CSV.  Throw OutputError.
#pragma once

#include <string>

#include "scene.hpp"

namespace cudahull::viewer {

void export_mesh(const Scene& scene, const std::string& path);
void export_trace(const Scene& scene, const std::string& path);
// Columns: index, kind (swap or removal), nx, ny, nz, d (the separating plane; empty for removals), above,
// below (route codes: a face id of the new mesh, or "entry K" for a chained decision entry, or "internal").
void export_decisions(const Scene& scene, const std::string& path);

}  // namespace cudahull::viewer

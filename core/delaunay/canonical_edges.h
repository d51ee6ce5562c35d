// The canonical edge numbering of core/delaunay/delaunay.h, for a triangulation numbered any
// other way (the sweep's, then flipped on a device): edges ordered by (smaller vertex id,
// larger vertex id), a the smaller. Two meshes of the same triangulation then agree record for
// record.
#pragma once

#include "mesh.h"

namespace ddt {

// Renumbers `mesh`'s edges canonically, turning each record whose a > b end for end.
void renumberCanonically(Mesh& mesh);

}  // namespace ddt

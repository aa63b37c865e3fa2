// The row layouts of the datasets a run writes (results, checkpoints): one row per node, per
// element (cell), per contact pair, or per item of a term (a gas chamber, a cable segment). Plain
// data below every layer, so the physics terms can say how their data is laid out without the io
// layer's HDF5 helpers (h5io.h).
#pragma once

namespace etfe {

enum class Layout { Nodes = 0, Cells = 1, Pairs = 2, Items = 3 };

} // namespace etfe

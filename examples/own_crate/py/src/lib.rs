//! `import my_turntable_py`: yarok's `World` and `Worlds` opening the showroom by its tag, and
//! template files using the turntable by its tag, beside yarok's bundled worlds.

use my_turntable::{Showroom, Turntable};

yarok_py::module!(
    my_turntable_py,
    yarok_py::Exports::new()
        .world::<Showroom>()
        .component::<Turntable>()
);

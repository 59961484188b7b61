//! Shared by the composition tests.

/// Declares a unit struct implementing `Component` with the given declaration.
macro_rules! component {
    ($name:ident, $declaration:expr) => {
        struct $name;
        impl yarok_core::component::Component for $name {
            fn declaration() -> yarok_core::component::Declaration {
                $declaration
            }
        }
    };
}

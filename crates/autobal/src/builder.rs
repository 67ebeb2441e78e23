//! Builders: start from a type's preset (its `Default`, each paper's base case), change what
//! differs with chained setters named as the fields, and `build()` validates, so that an invalid
//! description never reaches an analysis. Errors name the field as the config spells it.
//!
//! ```
//! use autobal::planar::PlanarRotor;
//! let rotor = PlanarRotor::builder().m3(0.01).c_psi(0.2).build().unwrap();
//! assert_eq!((rotor.m3, rotor.m1), (0.01, 1.0)); // the rest is paper 004's rotor
//! let e = PlanarRotor::builder().k(-1.0).build().unwrap_err();
//! assert!(e.to_string().starts_with("planar.k"));
//! ```

/// `builder!(Name for Target, |t| validation; field: type, ...)` defines `Name`, holding a
/// `Target` (starting from `Target::default()`), with one setter per field and `build()`.
macro_rules! builder {
    ($(#[$meta:meta])* $name:ident for $target:ty, $validate:expr; $($(#[$fm:meta])* $field:ident : $ty:ty),* $(,)?) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq)]
        pub struct $name {
            inner: $target,
        }

        impl Default for $name {
            fn default() -> Self {
                $name { inner: <$target>::default() }
            }
        }

        impl $name {
            /// Start from `from` instead of the default.
            pub fn from(from: $target) -> Self {
                $name { inner: from }
            }
            $(
                $(#[$fm])*
                #[doc = concat!("Set `", stringify!($field), "`.")]
                pub fn $field(mut self, value: $ty) -> Self {
                    self.inner.$field = value;
                    self
                }
            )*
            /// Validate and return the description (errors name the field).
            pub fn build(self) -> $crate::error::Result<$target> {
                let check: fn(&$target) -> $crate::error::Result<()> = $validate;
                check(&self.inner)?;
                Ok(self.inner)
            }
        }
    };
}

pub(crate) use builder;

//! One name per user-facing choice: the effect mode, the surface colour, the view, the GPU method
//! and the backend (each made a [`Choice`] beside its type by [`crate::choice!`]), and the tone
//! map. Each has its names, its one-line help texts and the message for a name it does not know
//! here, once; the scene file, the command line (clap), Python and the web page's address all
//! parse through [`Choice`].

use std::fmt;

use srt_color::ToneMap;

/// A closed set of named values that a person picks by name.
pub trait Choice: Copy + Eq + 'static {
    /// What the choice is called in messages ("effect mode", "method").
    const WHAT: &'static str;

    /// Every value, the default first where there is one.
    fn all() -> &'static [Self];

    /// The name used in scene files, on the command line, in Python and in addresses.
    fn name(self) -> &'static str;

    /// One line saying what the value does, for help texts.
    fn help(self) -> &'static str;

    /// Every name, in the order of [`Choice::all`].
    #[must_use]
    fn names() -> Vec<&'static str> {
        Self::all().iter().map(|value| value.name()).collect()
    }

    /// The value called `name`, if there is one.
    #[must_use]
    fn from_name(name: &str) -> Option<Self> {
        Self::all()
            .iter()
            .copied()
            .find(|value| value.name() == name)
    }

    /// The value called `name`.
    ///
    /// # Errors
    /// [`UnknownChoice`] naming the choice, the name given and the names there are.
    fn parse(name: &str) -> Result<Self, UnknownChoice> {
        Self::from_name(name).ok_or_else(|| UnknownChoice {
            what: Self::WHAT,
            given: name.to_owned(),
            names: Self::names(),
        })
    }
}

/// A name that is none of a choice's names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownChoice {
    /// What the choice is called ([`Choice::WHAT`]).
    pub what: &'static str,
    /// The name given.
    pub given: String,
    /// The names there are.
    pub names: Vec<&'static str>,
}

impl fmt::Display for UnknownChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown {} {:?}; expected ", self.what, self.given)?;
        let last = self.names.len().saturating_sub(1);
        for (i, name) in self.names.iter().enumerate() {
            let separator = match i {
                0 => "",
                _ if i == last => " or ",
                _ => ", ",
            };
            write!(f, "{separator}{name:?}")?;
        }
        Ok(())
    }
}

impl std::error::Error for UnknownChoice {}

/// Makes an enum of the calling crate a [`Choice`], from one table of its values: each value's
/// name and help line. Gives the enum `ALL` (the values in the table's order, the default first)
/// and `const fn name`, implements [`Choice`] with `what` as its [`Choice::WHAT`], and `Display`
/// (the name) and `FromStr` (through [`Choice::parse`]).
///
/// ```
/// #[derive(Debug, Clone, Copy, PartialEq, Eq)]
/// enum Speed {
///     Slow,
///     Fast,
/// }
/// srt_scene::choice!(Speed, "speed", {
///     Slow => "slow", "walking pace";
///     Fast => "fast", "near light speed";
/// });
/// assert_eq!("fast".parse::<Speed>(), Ok(Speed::Fast));
/// assert_eq!(Speed::ALL, [Speed::Slow, Speed::Fast]);
/// assert_eq!(
///     "medium".parse::<Speed>().unwrap_err().to_string(),
///     r#"unknown speed "medium"; expected "slow" or "fast""#
/// );
/// ```
#[macro_export]
macro_rules! choice {
    // The `Choice` impl alone, for a type that has its own `ALL` and `name` (srt-color's
    // `ToneMap`, which cannot depend on this crate).
    (@choice $choice:ty, $what:literal, { $($value:ident => $help:literal;)+ }) => {
        impl $crate::Choice for $choice {
            const WHAT: &'static str = $what;

            fn all() -> &'static [Self] {
                &Self::ALL
            }

            fn name(self) -> &'static str {
                Self::name(self)
            }

            fn help(self) -> &'static str {
                match self {
                    $(Self::$value => $help,)+
                }
            }
        }
    };
    ($choice:ty, $what:literal, { $($value:ident => $name:literal, $help:literal;)+ }) => {
        impl $choice {
            /// Every value, the default first (the order of `--help` and of messages).
            pub const ALL: [Self; [$($name),+].len()] = [$(Self::$value),+];

            /// The name used in scene files, on the command line, in Python and in addresses.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self {
                    $(Self::$value => $name,)+
                }
            }
        }

        $crate::choice!(@choice $choice, $what, { $($value => $help;)+ });

        impl ::core::fmt::Display for $choice {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                f.write_str(Self::name(*self))
            }
        }

        impl ::core::str::FromStr for $choice {
            type Err = $crate::UnknownChoice;

            fn from_str(name: &str) -> Result<Self, Self::Err> {
                <Self as $crate::Choice>::parse(name)
            }
        }
    };
}

crate::choice!(@choice ToneMap, "tone map", {
    Luminance => "Fig. 6 left: every temperature fully bright, only its hue shifts";
    Searchlight => "Fig. 6 right: brightness follows the radiance, on a log scale";
});

/// Serde for a [`Choice`] by its name (`#[serde(with = "choice::by_name")]`).
pub mod by_name {
    use serde::{Deserialize, Deserializer, Serializer, de};

    use super::Choice;

    /// Writes the value's name.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<T: Choice, S: Serializer>(value: &T, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(value.name())
    }

    /// Reads a name, refusing one the choice does not have ([`super::UnknownChoice`]).
    ///
    /// # Errors
    /// The deserializer's, or the unknown name's.
    pub fn deserialize<'de, T: Choice, D: Deserializer<'de>>(d: D) -> Result<T, D::Error> {
        let name = String::deserialize(d)?;
        T::parse(&name).map_err(de::Error::custom)
    }
}

/// Serde for an optional [`Choice`] by its name (absent: `None`).
pub mod by_optional_name {
    use serde::{Deserializer, Serializer};

    use super::Choice;

    /// Writes the value's name, or nothing.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<T: Choice, S: Serializer>(value: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
        match value {
            Some(value) => s.serialize_str(value.name()),
            None => s.serialize_none(),
        }
    }

    /// Reads a name as [`super::by_name`] does.
    ///
    /// # Errors
    /// The deserializer's, or the unknown name's.
    pub fn deserialize<'de, T: Choice, D: Deserializer<'de>>(d: D) -> Result<Option<T>, D::Error> {
        super::by_name::deserialize(d).map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Effects, SurfaceColour};
    use crate::view::View;

    fn round_trips<T: Choice + fmt::Debug>() {
        for &value in T::all() {
            assert_eq!(T::parse(value.name()), Ok(value));
            assert!(!value.help().is_empty(), "{value:?} has no help");
        }
        let names = T::names();
        let mut unique = names.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(
            unique.len(),
            names.len(),
            "{} names repeat: {names:?}",
            T::WHAT
        );
    }

    #[test]
    fn every_choice_parses_its_own_names_and_has_help() {
        round_trips::<Effects>();
        round_trips::<SurfaceColour>();
        round_trips::<View>();
        round_trips::<ToneMap>();
    }

    #[test]
    fn an_unknown_name_is_refused_with_every_name_there_is() {
        let error = View::parse("sideways").unwrap_err();
        assert_eq!(
            error.to_string(),
            r#"unknown view "sideways"; expected "seen", "measured" or "newtonian""#
        );
        assert_eq!(
            SurfaceColour::parse("sepia").unwrap_err().to_string(),
            r#"unknown surface colour "sepia"; expected "paper" or "spectral""#
        );
        assert_eq!("doppler".parse::<Effects>(), Ok(Effects::Doppler));
        assert_eq!(Effects::Searchlight.to_string(), "searchlight");
    }
}

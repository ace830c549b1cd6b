//! [`PerVariant`]: one value per variant of a lesson, indexed by the
//! variant itself (`self.maps[variant]`): a lesson's state per variant in
//! one typed place, instead of parallel `Vec`s indexed by `variant as
//! usize`, which only held while the enum's discriminants happened to
//! follow the order its values were made in.

use std::ops::{Index, IndexMut};

use clap::ValueEnum;

/// One `T` per variant of `V` (every variant, exercises too), in the
/// order `V::value_variants()` lists them.
#[derive(Clone, Debug)]
pub struct PerVariant<V, T> {
    values: Vec<T>,
    variant: std::marker::PhantomData<V>,
}

impl<V: ValueEnum + Copy + PartialEq, T> PerVariant<V, T> {
    /// `make(v)` for every variant `v`.
    pub fn new(make: impl FnMut(V) -> T) -> Self {
        let values = V::value_variants().iter().copied().map(make).collect();
        PerVariant {
            values,
            variant: std::marker::PhantomData,
        }
    }

    /// `make(v)` for every variant `v`, or its first error.
    pub fn try_new<E>(make: impl FnMut(V) -> Result<T, E>) -> Result<Self, E> {
        let values = V::value_variants().iter().copied().map(make);
        Ok(PerVariant {
            values: values.collect::<Result<_, E>>()?,
            variant: std::marker::PhantomData,
        })
    }

    /// Every variant with its value, in order.
    pub fn iter(&self) -> impl Iterator<Item = (V, &T)> {
        V::value_variants().iter().copied().zip(&self.values)
    }

    /// Every value, in the variants' order.
    pub fn values(&self) -> impl Iterator<Item = &T> {
        self.values.iter()
    }

    /// Every value, in the variants' order, to change.
    pub fn values_mut(&mut self) -> impl Iterator<Item = &mut T> {
        self.values.iter_mut()
    }

    /// The variant's place in `V::value_variants()` (the order the values
    /// were made in, which need not be the enum's discriminants).
    fn slot(variant: V) -> usize {
        let all = V::value_variants();
        let at = all.iter().position(|&v| v == variant);
        at.expect("a variant that value_variants() does not list (#[value(skip)]?)")
    }
}

impl<V: ValueEnum + Copy + PartialEq, T: Clone> PerVariant<V, T> {
    /// `value` for every variant.
    pub fn filled(value: T) -> Self {
        Self::new(|_| value.clone())
    }
}

impl<V: ValueEnum + Copy + PartialEq, T> Index<V> for PerVariant<V, T> {
    type Output = T;
    fn index(&self, variant: V) -> &T {
        &self.values[Self::slot(variant)]
    }
}

impl<V: ValueEnum + Copy + PartialEq, T> IndexMut<V> for PerVariant<V, T> {
    fn index_mut(&mut self, variant: V) -> &mut T {
        &mut self.values[Self::slot(variant)]
    }
}

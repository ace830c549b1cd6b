//! [`PerVariant`]: one value per variant of a lesson, indexed by the
//! variant itself (`self.maps[variant]`), never by `variant as usize`.

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

    fn slot(variant: V) -> usize {
        let all = V::value_variants();
        all.iter().position(|&v| v == variant).unwrap_or(all.len())
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

//! Lesson 03, PCF: filters that turn the shadow map into a fractional
//! visibility.

pub mod pcf;

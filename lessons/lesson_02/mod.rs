//! Lesson 02, bias: receiver-side bias in the lit pass, slope-scaled bias
//! in the shadow pass.

pub mod bias;

//! Test helpers: the loopback test server of `scenethesis_openai::testing`.
#![allow(unused_imports)]

pub use scenethesis_openai::testing::*;

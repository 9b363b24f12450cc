//! Lab records: reading them, their units, their cycles and branches, writing
//! them, and synthetic displacement histories.
//!
//! Every verb of `hyst` reads its data through this module, so everything it
//! returns is in the canonical units **mm, kN, s**, every value is finite, and
//! every problem with a file is an error naming the file, line and column and
//! what was expected:
//!
//! ```text
//! spd_369.csv:17:2: expected a number for column 'force_kN', found 'abc'
//! ```
//!
//! Nothing is dropped or assumed silently: what the reader skipped (on
//! request), ignored or assumed is in [`Record::notices`].
//!
//! # Reading
//!
//! ```
//! use hyst::data::{read_str, Channel, Format, ReadOptions};
//! let text = "# a test\ntime (s),displacement (in),force (kip)\n0,0,0\n1,0.5,2\n2,1,3\n";
//! let r = read_str("test.csv", text, Format::Csv, &ReadOptions::default())?;
//! assert_eq!(r.displacement().unwrap(), &[0.0, 12.7, 25.4]);
//! assert_eq!(r.input_channel(), Channel::Displacement);
//! assert_eq!(r.comments(), &["a test".to_string()]);
//! # Ok::<(), hyst::data::DataError>(())
//! ```
//!
//! Formats read ([`read`] picks by extension):
//!
//! | data set | form | how |
//! |---|---|---|
//! | `synthetic/` | `time (s),displacement (mm),force (kN)` after `#` lines | as is |
//! | `peer-spd-columns/fd/` | `disp_mm,force_kN`, no time | as is (rows in loading order) |
//! | `boucwen-benchmark/csv/` | `u_N,y_m`, 750 Hz, no time | as is: input force (the force column is named `u`); `sample_rate(750.0)` for a time base |
//! | `opensees-reference/` | `step,strain,stress,tangent` | as is: strain mm, stress kN assumed (notices), step checked, tangent not read |
//! | `opensees-reference/history.csv` | `step,strain` | a displacement history, no force |
//! | `clt-steel-plate-connection-tannert/` | names line, then units line `kN,mm`; force first | as is (roles from the units) |
//! | `mr-damper-dyke/` | `"t","A","D","Y","fs","V","F",` no units | needs options: `role("D", Displacement).unit("D", Centimetre).role("F", Force).unit("F", Newton)` (`Y` and `V` look like displacement and force by name) |
//! | `peer-spd-columns/raw_json/`, `cfs-fastener-peterman2014/`, `friction-damper-brfd/`, `steel-braces-simcenter/` | JSON | see [`json`] |
//! | `boucwen-benchmark/original_mat/` | MATLAB `.mat` | not read: the CSV copies are lossless |
//! | a spreadsheet's export (`.csv`, `.tsv`) | tabs or semicolons between fields, decimal comma | as is: the separator from a header without a comma, `1,5` read as 1.5 (a notice); `1,5` and `1.000` in one file refused |
//!
//! # Cycles and branches
//!
//! [`Cycles`] finds load reversals of the input signal with a threshold (a
//! reversal counts only after the signal moves back by more than it) and cuts
//! the record into half-cycles and cycles; [`Segmentation`] adds the branch
//! class of every sample (loading, unloading, reloading; see [`Branch`] and [`Segmentation`]),
//! the near-zero-force flag, the peak force of every half-cycle and the energy
//! of every cycle; [`Breakdown`] sums a model's squared residuals by cycle,
//! half-cycle, branch and zone.
//!
//! ```
//! use hyst::data::{Protocol, Record, SegmentOptions, Threshold};
//! let u = Protocol::opensees_reference().generate().unwrap();
//! let r = Record::from_history("history", u, None).unwrap();
//! let c = r.cycles(Threshold::default()).unwrap();
//! assert_eq!(c.reversals().len(), 36);
//! assert_eq!(c.complete_cycles(), 18);
//! ```
//!
//! # Writing
//!
//! [`write_record`] and [`write_columns`] write CSV that reads back to the
//! same `f64` values. The input channel is not written: a force-driven record
//! reads back as displacement-driven unless read with
//! `ReadOptions::input(Channel::Force)`.

pub mod baseline;
pub mod branches;
pub mod columns;
pub mod csv;
pub mod cycles;
mod error;
pub mod history;
pub mod json;
pub mod json_place;
mod read;
mod record;
pub mod residuals;
pub mod speed;
pub mod unique_keys;
pub mod units;
pub mod write;

pub use baseline::Baseline;
pub use branches::{Branch, Label, SegmentOptions, Segmentation};
pub use columns::Role;
pub use cycles::{Cycle, CycleError, Cycles, Direction, HalfCycle, Peak, Threshold};
pub use error::{DataError, Location};
pub use history::{HistoryError, Irregular, Normal, Protocol, Shape};
pub use json::JsonLayout;
pub use read::{read, read_str, read_text, ColumnRef, Format, ReadOptions};
pub use record::{Channel, Notice, Record, Series};
pub use residuals::{Breakdown, Tally};
pub use units::{Quantity, Unit};
pub use write::{write_columns, write_record, WriteError};

#[cfg(test)]
mod tests;

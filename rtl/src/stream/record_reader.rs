//! The set-up record reader shared by the stream tops (all eight: `pixel-stream`,
//! `textured-stream`, `gouraud-stream`, `cubic-stream`, `angular-stream`, `fast-stream`,
//! `quadric-stream`, `subdivision-stream`): the AXI4-Stream slave side that splits 32-bit words
//! into records and says which payload word each accepted word is. The tops keep their word banks (generated from
//! `rtl::stream::layout`), which take word k of a record when `take_word` and `index` = k + 1.
//!
//! # Records
//! A header word (bits 3..0: the type; 1 is known, and 2, 3 and 4 when `len2`, `len3`, `len4`
//! ≠ 0), then the type's payload words (`len1` … `len4`), `tlast` on the last. A header with
//! `tlast` (no payload), an unknown type, a `tlast` before or after the type's length: the
//! record is dropped whole (up to its `tlast`) and `error` is set (sticky). A complete record
//! sets `pending`; until the top clears it (`take_record`, when it moves the record out of its
//! receive bank) no word is accepted.
//!
//! # Ports
//! | port | dir | format |
//! |---|---|---|
//! | `head`, `tvalid`, `tlast` | in | the set-up stream (`s_axis_*`): `head` is `tdata`'s bits 3..0, all of a word the reader reads (the type, when it is a header) |
//! | `len1`, `len2`, `len3`, `len4` | in | `INDEX_BITS` (7) bits: payload words of record types 1 … 4 (≤ 127; `len2` = 0: type 2 unknown, likewise `len3`, `len4`) |
//! | `take_record` | in | the top takes the pending record this clock |
//! | `tready` | out | `s_axis_tready`: low only while a complete record is pending |
//! | `take_word` | out | this clock's word is payload word `index` − 1 of a record of a known length |
//! | `index` | out | `INDEX_BITS` (7) bits: 0 while a header is expected, else the payload word's number + 1 |
//! | `rec_type` | out | the current (or pending) record's type |
//! | `pending` | out | a complete, well-formed record waits |
//! | `error` | out | sticky: a record was dropped |
//!
//! # Latency, throughput
//! A word per clock while nothing is pending; `pending` rises in the clock after the record's
//! last word, and `tready` falls with it. No arithmetic, no overflow (a record longer than
//! 127 payload words is longer than every known type and dropped).

use rust_hdl::prelude::*;

/// Width of the word count (`len1` … `len4`, `index`): records of up to 127 payload words
/// (`subdivision-stream`'s parent record has 72).
pub const INDEX_BITS: usize = 7;

crate::hw_block! {
    /// The set-up record reader (see the module header).
    pub struct RecordReader(clock) {
        in {
            head: Bits<4>, tvalid: Bit, tlast: Bit, len1: Bits<INDEX_BITS>, len2: Bits<INDEX_BITS>,
            len3: Bits<INDEX_BITS>, len4: Bits<INDEX_BITS>, take_record: Bit,
        }
        out {
            tready: Bit, take_word: Bit, index: Bits<INDEX_BITS>, rec_type: Bits<4>, pending: Bit,
            error: Bit,
        }
        count: DFF<Bits<INDEX_BITS>>, type_q: DFF<Bits<4>>, pend: DFF<Bit>, skip: DFF<Bit>,
        err: DFF<Bit>,
        accept: Signal<Local, Bit>, take: Signal<Local, Bit>, known: Signal<Local, Bit>,
        head_known: Signal<Local, Bit>, expected: Signal<Local, Bits<INDEX_BITS>>,
        at_end: Signal<Local, Bit>, head_type: Signal<Local, Bits<4>>,
    }
}

impl Logic for RecordReader {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, count, type_q, pend, skip, err);
        self.tready.next = !self.pend.q.val();
        self.accept.next = self.tvalid.val() & !self.pend.q.val();
        self.take.next = self.accept.val() & !self.skip.q.val() & (self.count.q.val() != 0);
        self.known.next = (self.type_q.q.val() == 1)
            | ((self.type_q.q.val() == 2) & (self.len2.val() != 0))
            | ((self.type_q.q.val() == 3) & (self.len3.val() != 0))
            | ((self.type_q.q.val() == 4) & (self.len4.val() != 0));
        self.head_type.next = self.head.val();
        self.head_known.next = (self.head_type.val() == 1)
            | ((self.head_type.val() == 2) & (self.len2.val() != 0))
            | ((self.head_type.val() == 3) & (self.len3.val() != 0))
            | ((self.head_type.val() == 4) & (self.len4.val() != 0));
        self.expected.next = self.len2.val();
        if self.type_q.q.val() == 1 {
            self.expected.next = self.len1.val();
        }
        if self.type_q.q.val() == 3 {
            self.expected.next = self.len3.val();
        }
        if self.type_q.q.val() == 4 {
            self.expected.next = self.len4.val();
        }
        self.at_end.next = self.count.q.val() == self.expected.val();
        if self.accept.val() & self.skip.q.val() {
            // Dropping a bad record up to its tlast.
            if self.tlast.val() {
                self.skip.d.next = false;
            }
        } else if self.accept.val() & (self.count.q.val() == 0) {
            // Header.
            self.type_q.d.next = self.head_type.val();
            self.count.d.next = 1.into();
            if self.tlast.val() {
                // A record without payload.
                self.err.d.next = true;
                self.count.d.next = 0.into();
            } else if !self.head_known.val() {
                self.err.d.next = true;
                self.skip.d.next = true;
                self.count.d.next = 0.into();
            }
        } else if self.take.val() {
            self.count.d.next = self.count.q.val() + 1;
            if self.tlast.val() {
                self.count.d.next = 0.into();
                if self.at_end.val() & self.known.val() {
                    self.pend.d.next = true;
                } else {
                    self.err.d.next = true;
                }
            } else if self.at_end.val() {
                // Longer than its type: drop the rest.
                self.err.d.next = true;
                self.skip.d.next = true;
                self.count.d.next = 0.into();
            }
        }
        if self.take_record.val() {
            self.pend.d.next = false;
        }
        self.take_word.next = self.take.val();
        self.index.next = self.count.q.val();
        self.rec_type.next = self.type_q.q.val();
        self.pending.next = self.pend.q.val();
        self.error.next = self.err.q.val();
    }
}

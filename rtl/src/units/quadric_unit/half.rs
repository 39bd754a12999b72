//! One 32-bit half of the quadric unit's words (the tracker over the line starts and the line
//! generator, three channels), and the bits that cross from the low half to the high half.
//!
//! Not exported alone. Ports: the clock's control (`ystep xstep neg big ld hand hdir gadv`), the
//! load's 32-bit word halves per channel (`ri … bc`), the crossing bits in (`cin_r/g/b`, 29
//! bits, indexed by [`cross`]); out: this clock's crossing bits (`cout_*`, combinational) and
//! the generator pair's word halves (`p_*`, `q_*`, 32 bits, registers). Latency 1 clock: every
//! word is a register stepped each clock (the unit feeds the high half the low half's
//! registered `cout_*`, so the high half is one clock behind: see the unit's header); words
//! wrap modulo 2³² by design.

use rust_hdl::prelude::*;

/// The bits that cross from a word's low half to its high half (`QuadricHalf`'s `cin_*` and
/// `cout_*`, one vector per channel), by index: each add's carry out of bit 31, each
/// carry-save carry word's and each one-place shift's bit 31.
pub mod cross {
    /// `IP1`
    pub const IP1: usize = 0;
    /// `CKM1`
    pub const CKM1: usize = 1;
    /// `IM1`
    pub const IM1: usize = 2;
    /// `TDX31`
    pub const TDX31: usize = 3;
    /// `XIK`
    pub const XIK: usize = 4;
    /// `XI`
    pub const XI: usize = 5;
    /// `TA231`
    pub const TA231: usize = 6;
    /// `DXP1`
    pub const DXP1: usize = 7;
    /// `DXP2`
    pub const DXP2: usize = 8;
    /// `DXM1`
    pub const DXM1: usize = 9;
    /// `DXM2`
    pub const DXM2: usize = 10;
    /// `TC31`
    pub const TC31: usize = 11;
    /// `DYP1`
    pub const DYP1: usize = 12;
    /// `DYP2`
    pub const DYP2: usize = 13;
    /// `DYM1`
    pub const DYM1: usize = 14;
    /// `DYM2`
    pub const DYM2: usize = 15;
    /// `YI`
    pub const YI: usize = 16;
    /// `YDY`
    pub const YDY: usize = 17;
    /// `YDX`
    pub const YDX: usize = 18;
    /// `WA231`
    pub const WA231: usize = 19;
    /// `TA3`
    pub const TA3: usize = 20;
    /// `GE31`
    pub const GE31: usize = 21;
    /// `GPK`
    pub const GPK: usize = 22;
    /// `GP`
    pub const GP: usize = 23;
    /// `GQK`
    pub const GQK: usize = 24;
    /// `GQ`
    pub const GQ: usize = 25;
    /// `GA231`
    pub const GA231: usize = 26;
    /// `GE`
    pub const GE: usize = 27;
    /// `HGE`
    pub const HGE: usize = 28;
    /// How many.
    pub const BITS: usize = 29;
    /// The low half's carries in: a subtraction's +1 (its add's carry in) and the hand-over's
    /// I − Dx + 2A (the carry word's free bit 0); the x-step's −Dx's +1 is `XIK`, set with
    /// `neg`.
    pub const LOW: u64 =
        (1 << CKM1) | (1 << DXM1) | (1 << DXM2) | (1 << DYM1) | (1 << DYM2) | (1 << HGE);
}

crate::hw_block! {
    /// One 32-bit half of every word of the tracker and the generator, three channels (see the
    /// module header): the low half with the control of this clock and constant carries in,
    /// the high half with the control and the low half's `cout_*` of the clock before.
    pub struct QuadricHalf(clock) {
        in {
            ystep: Bit, xstep: Bit, neg: Bit, big: Bit, ld: Bit, hand: Bit, hdir: Bit, gadv: Bit,
            ri: Bits<32>, rdx: Bits<32>, rdy: Bits<32>, ra: Bits<32>, rb: Bits<32>, rc: Bits<32>,
            gi: Bits<32>, gdx: Bits<32>, gdy: Bits<32>, ga: Bits<32>, gb: Bits<32>, gc: Bits<32>,
            bi: Bits<32>, bdx: Bits<32>, bdy: Bits<32>, ba: Bits<32>, bb: Bits<32>, bc: Bits<32>,
            cin_r: Bits<29>, cin_g: Bits<29>, cin_b: Bits<29>,
        }
        out {
            cout_r: Bits<29>, cout_g: Bits<29>, cout_b: Bits<29>,
            p_r: Bits<32>, p_g: Bits<32>, p_b: Bits<32>, q_r: Bits<32>, q_g: Bits<32>, q_b: Bits<32>,
        }
        /// The tracker's I, Dx, Dy, 2A, 3·2A, 2B, C; the generator's pair p, q, its 2A, 3·2A
        /// and difference e = q − p.
        ti: [DFF<Bits<32>>; 3], tdx: [DFF<Bits<32>>; 3], tdy: [DFF<Bits<32>>; 3],
        ta2: [DFF<Bits<32>>; 3], ta3: [DFF<Bits<32>>; 3], tb2: [DFF<Bits<32>>; 3],
        tc: [DFF<Bits<32>>; 3], p: [DFF<Bits<32>>; 3], q: [DFF<Bits<32>>; 3],
        ga2: [DFF<Bits<32>>; 3], ga3: [DFF<Bits<32>>; 3], ge: [DFF<Bits<32>>; 3],
        w_i: [Signal<Local, Bits<32>>; 3], w_dx: [Signal<Local, Bits<32>>; 3],
        w_dy: [Signal<Local, Bits<32>>; 3], w_a2: [Signal<Local, Bits<32>>; 3],
        w_b2: [Signal<Local, Bits<32>>; 3], w_c: [Signal<Local, Bits<32>>; 3],
        s_tdx: [Signal<Local, Bits<32>>; 3], n_dx: [Signal<Local, Bits<32>>; 3],
        n_sdx: [Signal<Local, Bits<32>>; 3], m_im1: [Signal<Local, Bits<32>>; 3],
        x_im1: [Signal<Local, Bits<32>>; 3], k_im1: [Signal<Local, Bits<32>>; 3],
        xt1: [Signal<Local, Bits<32>>; 3], xt2: [Signal<Local, Bits<32>>; 3],
        m_xi: [Signal<Local, Bits<32>>; 3], x_xi: [Signal<Local, Bits<32>>; 3],
        k_xi: [Signal<Local, Bits<32>>; 3], s_ta2: [Signal<Local, Bits<32>>; 3],
        n_ta2: [Signal<Local, Bits<32>>; 3], n_sta2: [Signal<Local, Bits<32>>; 3],
        s_tc: [Signal<Local, Bits<32>>; 3], n_tc: [Signal<Local, Bits<32>>; 3],
        n_stc: [Signal<Local, Bits<32>>; 3], s_wa2: [Signal<Local, Bits<32>>; 3],
        s_ge: [Signal<Local, Bits<32>>; 3], m_gp: [Signal<Local, Bits<32>>; 3],
        x_gp: [Signal<Local, Bits<32>>; 3], k_gp: [Signal<Local, Bits<32>>; 3],
        m_gq: [Signal<Local, Bits<32>>; 3], x_gq: [Signal<Local, Bits<32>>; 3],
        k_gq: [Signal<Local, Bits<32>>; 3], s_ga2: [Signal<Local, Bits<32>>; 3],
        cin: [Signal<Local, Bits<29>>; 3], cout: [Signal<Local, Bits<29>>; 3],
        /// Each add, a + b + carry in (`cs_*`, one carry chain with its carry in), and its
        /// carries (`cy_*` = a·b + (a ⊕ b)·¬sum, bit by bit; only bit 31, the carry out, is read).
        cs_ip1: [Signal<Local, Bits<32>>; 3], cs_im1: [Signal<Local, Bits<32>>; 3],
        cs_xi: [Signal<Local, Bits<32>>; 3], cs_dxp1: [Signal<Local, Bits<32>>; 3],
        cs_dxp2: [Signal<Local, Bits<32>>; 3], cs_dxm1: [Signal<Local, Bits<32>>; 3],
        cs_dxm2: [Signal<Local, Bits<32>>; 3], cs_dyp1: [Signal<Local, Bits<32>>; 3],
        cs_dyp2: [Signal<Local, Bits<32>>; 3], cs_dym1: [Signal<Local, Bits<32>>; 3],
        cs_dym2: [Signal<Local, Bits<32>>; 3], cs_yi: [Signal<Local, Bits<32>>; 3],
        cs_ydy: [Signal<Local, Bits<32>>; 3], cs_ydx: [Signal<Local, Bits<32>>; 3],
        cs_ta3: [Signal<Local, Bits<32>>; 3], cs_gp: [Signal<Local, Bits<32>>; 3],
        cs_gq: [Signal<Local, Bits<32>>; 3], cs_ge: [Signal<Local, Bits<32>>; 3],
        cs_hge: [Signal<Local, Bits<32>>; 3],
        cy_ip1: [Signal<Local, Bits<32>>; 3], cy_im1: [Signal<Local, Bits<32>>; 3],
        cy_xi: [Signal<Local, Bits<32>>; 3], cy_dxp1: [Signal<Local, Bits<32>>; 3],
        cy_dxp2: [Signal<Local, Bits<32>>; 3], cy_dxm1: [Signal<Local, Bits<32>>; 3],
        cy_dxm2: [Signal<Local, Bits<32>>; 3], cy_dyp1: [Signal<Local, Bits<32>>; 3],
        cy_dyp2: [Signal<Local, Bits<32>>; 3], cy_dym1: [Signal<Local, Bits<32>>; 3],
        cy_dym2: [Signal<Local, Bits<32>>; 3], cy_yi: [Signal<Local, Bits<32>>; 3],
        cy_ydy: [Signal<Local, Bits<32>>; 3], cy_ydx: [Signal<Local, Bits<32>>; 3],
        cy_ta3: [Signal<Local, Bits<32>>; 3], cy_gp: [Signal<Local, Bits<32>>; 3],
        cy_gq: [Signal<Local, Bits<32>>; 3], cy_ge: [Signal<Local, Bits<32>>; 3],
        cy_hge: [Signal<Local, Bits<32>>; 3],
    }
}

// The three channels are one text repeated by `seq!` (channel `C` indexes every array with
// `[C]`); the exported Verilog is that text written out three times.
seq_macro::seq!(C in 0..3 {
impl Logic for QuadricHalf {
    #[hdl_gen]
    fn update(&mut self) {
        for c in 0..3 {
            self.ti[c].clock.next = self.clock.val();
            self.ti[c].d.next = self.ti[c].q.val();
            self.tdx[c].clock.next = self.clock.val();
            self.tdx[c].d.next = self.tdx[c].q.val();
            self.tdy[c].clock.next = self.clock.val();
            self.tdy[c].d.next = self.tdy[c].q.val();
            self.ta2[c].clock.next = self.clock.val();
            self.ta2[c].d.next = self.ta2[c].q.val();
            self.ta3[c].clock.next = self.clock.val();
            self.ta3[c].d.next = self.ta3[c].q.val();
            self.tb2[c].clock.next = self.clock.val();
            self.tb2[c].d.next = self.tb2[c].q.val();
            self.tc[c].clock.next = self.clock.val();
            self.tc[c].d.next = self.tc[c].q.val();
            self.p[c].clock.next = self.clock.val();
            self.p[c].d.next = self.p[c].q.val();
            self.q[c].clock.next = self.clock.val();
            self.q[c].d.next = self.q[c].q.val();
            self.ga2[c].clock.next = self.clock.val();
            self.ga2[c].d.next = self.ga2[c].q.val();
            self.ga3[c].clock.next = self.clock.val();
            self.ga3[c].d.next = self.ga3[c].q.val();
            self.ge[c].clock.next = self.clock.val();
            self.ge[c].d.next = self.ge[c].q.val();
        }
        self.w_i[0].next = self.ri.val();
        self.w_dx[0].next = self.rdx.val();
        self.w_dy[0].next = self.rdy.val();
        self.w_a2[0].next = self.ra.val();
        self.w_b2[0].next = self.rb.val();
        self.w_c[0].next = self.rc.val();
        self.cin[0].next = self.cin_r.val();
        self.w_i[1].next = self.gi.val();
        self.w_dx[1].next = self.gdx.val();
        self.w_dy[1].next = self.gdy.val();
        self.w_a2[1].next = self.ga.val();
        self.w_b2[1].next = self.gb.val();
        self.w_c[1].next = self.gc.val();
        self.cin[1].next = self.cin_g.val();
        self.w_i[2].next = self.bi.val();
        self.w_dx[2].next = self.bdx.val();
        self.w_dy[2].next = self.bdy.val();
        self.w_a2[2].next = self.ba.val();
        self.w_b2[2].next = self.bb.val();
        self.w_c[2].next = self.bc.val();
        self.cin[2].next = self.cin_b.val();
        #(
        // Channel C.
        // The hand-over's pair: I + Dx; I − Dx + 2A (carry-save, the +1 in bit 0's carry).
        self.cs_ip1[C].next = self.ti[C].q.val()
            + self.tdx[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(0));
        self.cy_ip1[C].next = (self.ti[C].q.val() & self.tdx[C].q.val())
            | ((self.ti[C].q.val() ^ self.tdx[C].q.val()) & !self.cs_ip1[C].val());
        self.n_dx[C].next = !self.tdx[C].q.val();
        self.x_im1[C].next = self.ti[C].q.val() ^ self.n_dx[C].val() ^ self.ta2[C].q.val();
        self.m_im1[C].next = (self.ti[C].q.val() & self.n_dx[C].val())
            | (self.ti[C].q.val() & self.ta2[C].q.val())
            | (self.n_dx[C].val() & self.ta2[C].q.val());
        self.k_im1[C].next =
            (self.m_im1[C].val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(1));
        self.cs_im1[C].next = self.x_im1[C].val()
            + self.k_im1[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(2));
        self.cy_im1[C].next = (self.x_im1[C].val() & self.k_im1[C].val())
            | ((self.x_im1[C].val() ^ self.k_im1[C].val()) & !self.cs_im1[C].val());
        // The x-step's terms: I + (Dx | 2·Dx + 2A | −Dx + 2A | −2·Dx + 3·2A).
        self.s_tdx[C].next =
            (self.tdx[C].q.val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(3));
        self.n_sdx[C].next = !self.s_tdx[C].val();
        if self.neg.val() {
            if self.big.val() {
                self.xt1[C].next = self.n_sdx[C].val();
                self.xt2[C].next = self.ta3[C].q.val();
            } else {
                self.xt1[C].next = self.n_dx[C].val();
                self.xt2[C].next = self.ta2[C].q.val();
            }
        } else if self.big.val() {
            self.xt1[C].next = self.s_tdx[C].val();
            self.xt2[C].next = self.ta2[C].q.val();
        } else {
            self.xt1[C].next = self.tdx[C].q.val();
            self.xt2[C].next = 0.into();
        }
        self.x_xi[C].next = self.ti[C].q.val() ^ self.xt1[C].val() ^ self.xt2[C].val();
        self.m_xi[C].next = (self.ti[C].q.val() & self.xt1[C].val())
            | (self.ti[C].q.val() & self.xt2[C].val())
            | (self.xt1[C].val() & self.xt2[C].val());
        self.k_xi[C].next =
            (self.m_xi[C].val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(4));
        self.cs_xi[C].next = self.x_xi[C].val()
            + self.k_xi[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(5));
        self.cy_xi[C].next = (self.x_xi[C].val() & self.k_xi[C].val())
            | ((self.x_xi[C].val() ^ self.k_xi[C].val()) & !self.cs_xi[C].val());
        // Dx ± 2A·step, Dy ± C·step: two-operand adds, selected after the carry chains.
        self.s_ta2[C].next =
            (self.ta2[C].q.val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(6));
        self.n_ta2[C].next = !self.ta2[C].q.val();
        self.n_sta2[C].next = !self.s_ta2[C].val();
        self.cs_dxp1[C].next = self.tdx[C].q.val()
            + self.ta2[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(7));
        self.cy_dxp1[C].next = (self.tdx[C].q.val() & self.ta2[C].q.val())
            | ((self.tdx[C].q.val() ^ self.ta2[C].q.val()) & !self.cs_dxp1[C].val());
        self.cs_dxp2[C].next = self.tdx[C].q.val()
            + self.s_ta2[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(8));
        self.cy_dxp2[C].next = (self.tdx[C].q.val() & self.s_ta2[C].val())
            | ((self.tdx[C].q.val() ^ self.s_ta2[C].val()) & !self.cs_dxp2[C].val());
        self.cs_dxm1[C].next = self.tdx[C].q.val()
            + self.n_ta2[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(9));
        self.cy_dxm1[C].next = (self.tdx[C].q.val() & self.n_ta2[C].val())
            | ((self.tdx[C].q.val() ^ self.n_ta2[C].val()) & !self.cs_dxm1[C].val());
        self.cs_dxm2[C].next = self.tdx[C].q.val()
            + self.n_sta2[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(10));
        self.cy_dxm2[C].next = (self.tdx[C].q.val() & self.n_sta2[C].val())
            | ((self.tdx[C].q.val() ^ self.n_sta2[C].val()) & !self.cs_dxm2[C].val());
        self.s_tc[C].next =
            (self.tc[C].q.val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(11));
        self.n_tc[C].next = !self.tc[C].q.val();
        self.n_stc[C].next = !self.s_tc[C].val();
        self.cs_dyp1[C].next = self.tdy[C].q.val()
            + self.tc[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(12));
        self.cy_dyp1[C].next = (self.tdy[C].q.val() & self.tc[C].q.val())
            | ((self.tdy[C].q.val() ^ self.tc[C].q.val()) & !self.cs_dyp1[C].val());
        self.cs_dyp2[C].next = self.tdy[C].q.val()
            + self.s_tc[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(13));
        self.cy_dyp2[C].next = (self.tdy[C].q.val() & self.s_tc[C].val())
            | ((self.tdy[C].q.val() ^ self.s_tc[C].val()) & !self.cs_dyp2[C].val());
        self.cs_dym1[C].next = self.tdy[C].q.val()
            + self.n_tc[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(14));
        self.cy_dym1[C].next = (self.tdy[C].q.val() & self.n_tc[C].val())
            | ((self.tdy[C].q.val() ^ self.n_tc[C].val()) & !self.cs_dym1[C].val());
        self.cs_dym2[C].next = self.tdy[C].q.val()
            + self.n_stc[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(15));
        self.cy_dym2[C].next = (self.tdy[C].q.val() & self.n_stc[C].val())
            | ((self.tdy[C].q.val() ^ self.n_stc[C].val()) & !self.cs_dym2[C].val());
        // The y-step: I + Dy, Dy + 2B, Dx + C.
        self.cs_yi[C].next = self.ti[C].q.val()
            + self.tdy[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(16));
        self.cy_yi[C].next = (self.ti[C].q.val() & self.tdy[C].q.val())
            | ((self.ti[C].q.val() ^ self.tdy[C].q.val()) & !self.cs_yi[C].val());
        self.cs_ydy[C].next = self.tdy[C].q.val()
            + self.tb2[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(17));
        self.cy_ydy[C].next = (self.tdy[C].q.val() & self.tb2[C].q.val())
            | ((self.tdy[C].q.val() ^ self.tb2[C].q.val()) & !self.cs_ydy[C].val());
        self.cs_ydx[C].next = self.tdx[C].q.val()
            + self.tc[C].q.val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(18));
        self.cy_ydx[C].next = (self.tdx[C].q.val() & self.tc[C].q.val())
            | ((self.tdx[C].q.val() ^ self.tc[C].q.val()) & !self.cs_ydx[C].val());
        // The load's 3·2A.
        self.s_wa2[C].next =
            (self.w_a2[C].val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(19));
        self.cs_ta3[C].next = self.s_wa2[C].val()
            + self.w_a2[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(20));
        self.cy_ta3[C].next = (self.s_wa2[C].val() & self.w_a2[C].val())
            | ((self.s_wa2[C].val() ^ self.w_a2[C].val()) & !self.cs_ta3[C].val());
        // The generator: p' = q + e + 2A, q' = q + 2e + 3·2A, e' = e + 2·2A; a hand-over's e = 2A − Dx.
        self.s_ge[C].next =
            (self.ge[C].q.val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(21));
        self.x_gp[C].next = self.q[C].q.val() ^ self.ge[C].q.val() ^ self.ga2[C].q.val();
        self.m_gp[C].next = (self.q[C].q.val() & self.ge[C].q.val())
            | (self.q[C].q.val() & self.ga2[C].q.val())
            | (self.ge[C].q.val() & self.ga2[C].q.val());
        self.k_gp[C].next =
            (self.m_gp[C].val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(22));
        self.cs_gp[C].next = self.x_gp[C].val()
            + self.k_gp[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(23));
        self.cy_gp[C].next = (self.x_gp[C].val() & self.k_gp[C].val())
            | ((self.x_gp[C].val() ^ self.k_gp[C].val()) & !self.cs_gp[C].val());
        self.x_gq[C].next = self.q[C].q.val() ^ self.s_ge[C].val() ^ self.ga3[C].q.val();
        self.m_gq[C].next = (self.q[C].q.val() & self.s_ge[C].val())
            | (self.q[C].q.val() & self.ga3[C].q.val())
            | (self.s_ge[C].val() & self.ga3[C].q.val());
        self.k_gq[C].next =
            (self.m_gq[C].val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(24));
        self.cs_gq[C].next = self.x_gq[C].val()
            + self.k_gq[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(25));
        self.cy_gq[C].next = (self.x_gq[C].val() & self.k_gq[C].val())
            | ((self.x_gq[C].val() ^ self.k_gq[C].val()) & !self.cs_gq[C].val());
        self.s_ga2[C].next =
            (self.ga2[C].q.val() << 1) | bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(26));
        self.cs_ge[C].next = self.ge[C].q.val()
            + self.s_ga2[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(27));
        self.cy_ge[C].next = (self.ge[C].q.val() & self.s_ga2[C].val())
            | ((self.ge[C].q.val() ^ self.s_ga2[C].val()) & !self.cs_ge[C].val());
        self.cs_hge[C].next = self.ta2[C].q.val()
            + self.n_dx[C].val()
            + bit_cast::<32, 1>(self.cin[C].val().get_bits::<1>(28));
        self.cy_hge[C].next = (self.ta2[C].q.val() & self.n_dx[C].val())
            | ((self.ta2[C].q.val() ^ self.n_dx[C].val()) & !self.cs_hge[C].val());
        // What leaves bit 31: each add's carry, each carry word's and each shift's top bit.
        self.cout[C].next = bit_cast::<29, 1>(self.cy_ip1[C].val().get_bits::<1>(31))
            | (bit_cast::<29, 1>(self.m_im1[C].val().get_bits::<1>(31)) << 1)
            | (bit_cast::<29, 1>(self.cy_im1[C].val().get_bits::<1>(31)) << 2)
            | (bit_cast::<29, 1>(self.tdx[C].q.val().get_bits::<1>(31)) << 3)
            | (bit_cast::<29, 1>(self.m_xi[C].val().get_bits::<1>(31)) << 4)
            | (bit_cast::<29, 1>(self.cy_xi[C].val().get_bits::<1>(31)) << 5)
            | (bit_cast::<29, 1>(self.ta2[C].q.val().get_bits::<1>(31)) << 6)
            | (bit_cast::<29, 1>(self.cy_dxp1[C].val().get_bits::<1>(31)) << 7)
            | (bit_cast::<29, 1>(self.cy_dxp2[C].val().get_bits::<1>(31)) << 8)
            | (bit_cast::<29, 1>(self.cy_dxm1[C].val().get_bits::<1>(31)) << 9)
            | (bit_cast::<29, 1>(self.cy_dxm2[C].val().get_bits::<1>(31)) << 10)
            | (bit_cast::<29, 1>(self.tc[C].q.val().get_bits::<1>(31)) << 11)
            | (bit_cast::<29, 1>(self.cy_dyp1[C].val().get_bits::<1>(31)) << 12)
            | (bit_cast::<29, 1>(self.cy_dyp2[C].val().get_bits::<1>(31)) << 13)
            | (bit_cast::<29, 1>(self.cy_dym1[C].val().get_bits::<1>(31)) << 14)
            | (bit_cast::<29, 1>(self.cy_dym2[C].val().get_bits::<1>(31)) << 15)
            | (bit_cast::<29, 1>(self.cy_yi[C].val().get_bits::<1>(31)) << 16)
            | (bit_cast::<29, 1>(self.cy_ydy[C].val().get_bits::<1>(31)) << 17)
            | (bit_cast::<29, 1>(self.cy_ydx[C].val().get_bits::<1>(31)) << 18)
            | (bit_cast::<29, 1>(self.w_a2[C].val().get_bits::<1>(31)) << 19)
            | (bit_cast::<29, 1>(self.cy_ta3[C].val().get_bits::<1>(31)) << 20)
            | (bit_cast::<29, 1>(self.ge[C].q.val().get_bits::<1>(31)) << 21)
            | (bit_cast::<29, 1>(self.m_gp[C].val().get_bits::<1>(31)) << 22)
            | (bit_cast::<29, 1>(self.cy_gp[C].val().get_bits::<1>(31)) << 23)
            | (bit_cast::<29, 1>(self.m_gq[C].val().get_bits::<1>(31)) << 24)
            | (bit_cast::<29, 1>(self.cy_gq[C].val().get_bits::<1>(31)) << 25)
            | (bit_cast::<29, 1>(self.ga2[C].q.val().get_bits::<1>(31)) << 26)
            | (bit_cast::<29, 1>(self.cy_ge[C].val().get_bits::<1>(31)) << 27)
            | (bit_cast::<29, 1>(self.cy_hge[C].val().get_bits::<1>(31)) << 28);
        // The registers: the y-step, the x-step, the load; the generator's step, the hand-over.
        if self.ystep.val() {
            self.ti[C].d.next = self.cs_yi[C].val();
            self.tdy[C].d.next = self.cs_ydy[C].val();
            self.tdx[C].d.next = self.cs_ydx[C].val();
        }
        if self.xstep.val() {
            self.ti[C].d.next = self.cs_xi[C].val();
            if self.neg.val() {
                if self.big.val() {
                    self.tdx[C].d.next = self.cs_dxm2[C].val();
                    self.tdy[C].d.next = self.cs_dym2[C].val();
                } else {
                    self.tdx[C].d.next = self.cs_dxm1[C].val();
                    self.tdy[C].d.next = self.cs_dym1[C].val();
                }
            } else if self.big.val() {
                self.tdx[C].d.next = self.cs_dxp2[C].val();
                self.tdy[C].d.next = self.cs_dyp2[C].val();
            } else {
                self.tdx[C].d.next = self.cs_dxp1[C].val();
                self.tdy[C].d.next = self.cs_dyp1[C].val();
            }
        }
        if self.ld.val() {
            self.ti[C].d.next = self.w_i[C].val();
            self.tdx[C].d.next = self.w_dx[C].val();
            self.tdy[C].d.next = self.w_dy[C].val();
            self.ta2[C].d.next = self.w_a2[C].val();
            self.ta3[C].d.next = self.cs_ta3[C].val();
            self.tb2[C].d.next = self.w_b2[C].val();
            self.tc[C].d.next = self.w_c[C].val();
        }
        if self.gadv.val() {
            self.p[C].d.next = self.cs_gp[C].val();
            self.q[C].d.next = self.cs_gq[C].val();
            self.ge[C].d.next = self.cs_ge[C].val();
        }
        if self.hand.val() {
            self.p[C].d.next = self.ti[C].q.val();
            self.ga2[C].d.next = self.ta2[C].q.val();
            self.ga3[C].d.next = self.ta3[C].q.val();
            if self.hdir.val() {
                self.q[C].d.next = self.cs_im1[C].val();
                self.ge[C].d.next = self.cs_hge[C].val();
            } else {
                self.q[C].d.next = self.cs_ip1[C].val();
                self.ge[C].d.next = self.tdx[C].q.val();
            }
        }
        )*
        self.cout_r.next = self.cout[0].val();
        self.p_r.next = self.p[0].q.val();
        self.q_r.next = self.q[0].q.val();
        self.cout_g.next = self.cout[1].val();
        self.p_g.next = self.p[1].q.val();
        self.q_g.next = self.q[1].q.val();
        self.cout_b.next = self.cout[2].val();
        self.p_b.next = self.p[2].q.val();
        self.q_b.next = self.q[2].q.val();
    }
}
});

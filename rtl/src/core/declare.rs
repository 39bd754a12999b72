//! One declaration per block: [`hw_block!`](crate::hw_block) writes a block's struct
//! (`#[derive(LogicBlock)]`, ports in row order, internal fields), its constructor, its
//! [`Dut`](crate::core::sim::Dut) view and, for an exported block, its
//! [`RtlBlock`](crate::core::registry::RtlBlock) facts — so a port is named once and the harness's
//! row order is the declaration order. [`hw_bundle!`](crate::hw_bundle) lets a composite
//! and its child share one list of ports.
//!
//! Not a block: no ports, no latency of its own.
//!
//! # `hw_block!`
//!
//! ```text
//! crate::hw_block! {
//!     /// Doc of the struct.
//!     pub struct MyBlock(clock) as "my-block" {  // `(clock)`: `pub clock: Signal<In, Clock>`;
//!                                                // `as NAME`: exported (--block my-block,
//!                                                // Verilog module my_block), then three facts:
//!         summary: "a and b in, y out (SPEC §n)",
//!         latency: 2 => "valid_in to valid_out, one input per clock",  // also MyBlock::LATENCY
//!         multipliers: 1,        // 16×16 multiplies: the SB_MAC16 count Yosys must map
//!         in { valid_in: Bit, a: Bits<16>, b: Bits<16> }  // Signal<In, _>, in row order
//!         out { valid_out: Bit, y: Bits<32> }           // Signal<Out, _>, in row order
//!         // Internal fields, several a line, with their full types; `= expr` initialises one
//!         // (a `Constant` needs it), every other field is `Default::default()`.
//!         a_p1: DFF<Bits<16>>, b_p1: DFF<Bits<16>>, y_q: DFF<Bits<32>>,
//!         half: Constant<Bits<32>> = Constant::new((1u64 << 14).into()),
//!         sum: Signal<Local, Bits<32>>,
//!     }
//!     new(c: &MyParams);     // optional, see below
//! }
//! ```
//! Constructor: without `new`, `impl Default`; `new();` gives `new()` and `Default`;
//! `new(c: &P);` gives `pub fn new(c: &P)` (the `= expr` initialisers may use `c`) and makes
//! `P` the registry's `Params` (`build(p)` is `new(p)`; otherwise `NoParams` and `default()`).
//! Ports may carry doc comments (`///`) and be written several a line; `pub` before an
//! internal field makes it public. Without `(clock)` the block is combinational and gets no
//! `Dut` view.
//!
//! # Port bundles
//!
//! A list of ports that a child and the composite around it both have (the address block's
//! set-up, the BVI's twelve words) is one macro, named in `in { … }` like a port:
//! ```text
//! #[macro_export]
//! macro_rules! my_setup_ports {
//!     ($($then:tt)*) => { $crate::hw_bundle! { [w_b0: Bits<12>, w_e0: Bits<13>] $($then)* } };
//! }
//! crate::hw_block! { pub struct Top(clock) { in { load: Bit, my_setup_ports!, c: Bit } … } }
//! ```
//!
//! # `update()`
//!
//! `impl Logic` with its `#[hdl_gen] fn update` is written by hand. `#[hdl_gen]` accepts no
//! macro inside `update()` but `dff_setup!`/`clock!`, so a macro that writes statements must
//! write the whole `impl Logic`; it compiles when the caller passes `#[hdl_gen]` and `self`
//! as tokens (`$pound:tt $attr:tt fn update(&mut $s:ident)`): the `connect()`/`hdl()` that
//! `#[hdl_gen]` adds then have the hygiene of the caller's statements. (With `#[hdl_gen]`
//! written in the macro's own text they take the expansion's `self`, which cannot see the
//! caller's.) [`hdl_update!`](crate::hdl_update) is that wrapper, with one statement of its
//! own: `forward CHILD <- BUNDLE!;` forwards a port bundle into a child
//! (`self.addr.w_b0.next = self.w_b0.val();` for each port):
//! ```text
//! crate::hdl_update! {
//!     impl Logic for Top {
//!         #[hdl_gen]
//!         fn update(&mut self) {
//!             { clock!(self, clock, addr); self.addr.load.next = self.load.val(); }
//!             forward addr <- my_setup_ports!;
//!             { self.y.next = self.addr.y.val(); }
//!         }
//!     }
//! }
//! ```
//! `lit_pipeline!` (`pipelines::pixel_pipeline`) writes the lit path of `pixel-pipeline` and
//! `textured-pipeline` once that way; [`two_lane_stream!`](crate::two_lane_stream),
//! [`one_lane_stream!`](crate::one_lane_stream) and `span_pipeline!` write whole blocks in
//! their own text (one hygiene). The Verilog is the text written out.

/// Declare a block once: struct, constructor, `Dut` view and registry facts. See the
/// [module documentation](crate::core::declare) for the syntax.
#[macro_export]
macro_rules! hw_block {
    // The `in` list, one entry at a time: a port, or a bundle macro that appends its ports.
    (@in [$($done:tt)*] [] $($state:tt)*) => {
        $crate::hw_block!(@parsed [$($done)*] $($state)*);
    };
    (@in [$($done:tt)*] [$bundle:ident ! $(, $($more:tt)*)?] $($state:tt)*) => {
        $crate::$bundle! { @ports [$($done)*] [$($($more)*)?] $($state)* }
    };
    (@in [$($done:tt)*] [$(#[$m:meta])* $p:ident : $t:ty $(, $($more:tt)*)?] $($state:tt)*) => {
        $crate::hw_block!(@in [$($done)* $(#[$m])* $p: $t,] [$($($more)*)?] $($state)*);
    };

    (@parsed [$($(#[$im:meta])* $i:ident : $it:ty,)*]
        {$(#[$sm:meta])* $vis:vis struct $name:ident [$($clk:ident)?] $reg:tt}
        {
            out { $($(#[$om:meta])* $o:ident : $ot:ty),* $(,)? }
            $($(#[$fm:meta])* $fv:vis $f:ident : $ft:ty $(= $fe:expr)?),* $(,)?
        }
        $(new($($arg:ident : &$pt:ty)?);)?
    ) => {
        $(#[$sm])*
        #[derive(rust_hdl::prelude::LogicBlock)]
        $vis struct $name {
            $(pub $clk: rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock>,)?
            $($(#[$im])* pub $i: rust_hdl::prelude::Signal<rust_hdl::prelude::In, $it>,)*
            $($(#[$om])* pub $o: rust_hdl::prelude::Signal<rust_hdl::prelude::Out, $ot>,)*
            $($(#[$fm])* $fv $f: $ft,)*
        }
        $crate::hw_block!(@ctor $name [$(new($($arg: &$pt)?))?]
            [$($clk)? $($i)* $($o)*] [$($f $(= $fe)?;)*]);
        $crate::hw_block!(@dut $name [$($clk)?] [$($i),*] [$($o),*]);
        $crate::hw_block!(@registry $name $reg [$(new($($arg: &$pt)?))?]);
    };

    (@ctor $name:ident [] $ports:tt $fields:tt) => {
        impl Default for $name {
            fn default() -> Self {
                $crate::hw_block!(@fields $ports $fields)
            }
        }
    };
    (@ctor $name:ident [new()] $ports:tt $fields:tt) => {
        impl $name {
            /// The block, every register at 0.
            pub fn new() -> Self {
                $crate::hw_block!(@fields $ports $fields)
            }
        }
        impl Default for $name {
            fn default() -> Self {
                Self::new()
            }
        }
    };
    (@ctor $name:ident [new($arg:ident : &$pt:ty)] $ports:tt $fields:tt) => {
        impl $name {
            /// The block built from its parameters, every register at 0.
            pub fn new($arg: &$pt) -> Self {
                $crate::hw_block!(@fields $ports $fields)
            }
        }
    };
    (@fields [$($port:ident)*] [$($f:ident $(= $fe:expr)?;)*]) => {
        Self {
            $($port: Default::default(),)*
            $($f: $crate::hw_block!(@init $($fe)?),)*
        }
    };
    (@init) => { Default::default() };
    (@init $e:expr) => { $e };

    (@dut $name:ident [] $i:tt $o:tt) => {};
    (@dut $name:ident [$clk:ident] [$($i:ident),*] [$($o:ident),*]) => {
        $crate::impl_dut!($name, clock: $clk, inputs: [$($i),*], outputs: [$($o),*]);
    };

    (@registry $name:ident [] $ctor:tt) => {};
    (@registry $name:ident [$n:literal $s:literal $lat:expr, $lm:literal $mul:expr] $ctor:tt) => {
        impl $name {
            #[doc = concat!("Latency in clocks: ", $lm, ".")]
            pub const LATENCY: usize = $lat;
        }
        impl $crate::core::registry::RtlBlock for $name {
            type Params = $crate::hw_block!(@params $ctor);
            const NAME: &'static str = $n;
            const SUMMARY: &'static str = $s;
            const LATENCY: usize = $name::LATENCY;
            const LATENCY_MEANING: &'static str = $lm;
            const MULTIPLIERS: usize = $mul;
            fn build(p: &Self::Params) -> Self {
                $crate::hw_block!(@build p $ctor)
            }
        }
    };
    (@params [new($arg:ident : &$pt:ty)]) => { $pt };
    (@params $other:tt) => { $crate::core::registry::NoParams };
    (@build $p:ident [new($arg:ident : &$pt:ty)]) => { Self::new($p) };
    (@build $p:ident [new()]) => {{ let _ = $p; Self::new() }};
    (@build $p:ident []) => {{ let _ = $p; Self::default() }};

    // Entry: an exported block (`as NAME` and its facts) or an internal one; the `in` list
    // goes to the muncher above.
    (
        $(#[$sm:meta])*
        $vis:vis struct $name:ident $(($clk:ident))? as $n:literal {
            summary: $s:literal,
            latency: $lat:expr => $lm:literal,
            multipliers: $mul:expr,
            in { $($ins:tt)* }
            $($body:tt)*
        }
        $($tail:tt)*
    ) => {
        $crate::hw_block!(@in [] [$($ins)*]
            {$(#[$sm])* $vis struct $name [$($clk)?] [$n $s $lat, $lm $mul]} {$($body)*} $($tail)*);
    };
    (
        $(#[$sm:meta])*
        $vis:vis struct $name:ident $(($clk:ident))? {
            in { $($ins:tt)* }
            $($body:tt)*
        }
        $($tail:tt)*
    ) => {
        $crate::hw_block!(@in [] [$($ins)*]
            {$(#[$sm])* $vis struct $name [$($clk)?] []} {$($body)*} $($tail)*);
    };
}

/// The body of a port-bundle macro (see the [module documentation](crate::core::declare)): appends
/// the bundle's ports to a [`hw_block!`](crate::hw_block) `in` list.
#[macro_export]
macro_rules! hw_bundle {
    ([$($p:ident : $t:ty),* $(,)?] @ports [$($done:tt)*] $($state:tt)*) => {
        $crate::hw_block!(@in [$($done)* $($p: $t,)*] $($state)*);
    };
    // The bundle's port names, for `hdl_update!`'s `forward`.
    ([$($p:ident : $t:ty),* $(,)?] @names $($state:tt)*) => {
        $crate::hdl_update!(@forwarded [$($p)*] $($state)*);
    };
}

/// An `impl Logic` whose `update` forwards port bundles into a child: the body is a sequence
/// of statement groups `{ … }` and lines `forward CHILD <- BUNDLE!;`, each of which becomes
/// `self.CHILD.PORT.next = self.PORT.val();` for every port of the bundle, in its order (see
/// the [module documentation](crate::core::declare)). The caller writes `#[hdl_gen]` and
/// `self`, so that its statements and the functions `#[hdl_gen]` adds have one hygiene.
#[macro_export]
macro_rules! hdl_update {
    (
        impl Logic for $name:ident {
            $pound:tt $attr:tt
            fn update(&mut $s:ident) { $($body:tt)* }
        }
    ) => {
        $crate::hdl_update!(@munch [$name $pound $attr $s] [] $($body)*);
    };
    (@munch $head:tt [$($done:tt)*] { $($stmts:tt)* } $($rest:tt)*) => {
        $crate::hdl_update!(@munch $head [$($done)* $($stmts)*] $($rest)*);
    };
    (@munch $head:tt $done:tt forward $child:ident <- $bundle:ident ! ; $($rest:tt)*) => {
        $crate::$bundle! { @names $head $done $child [$($rest)*] }
    };
    (@forwarded [$($p:ident)*] [$name:ident $pound:tt $attr:tt $s:ident] [$($done:tt)*]
        $child:ident [$($rest:tt)*]) => {
        $crate::hdl_update!(@munch [$name $pound $attr $s]
            [$($done)* $($s.$child.$p.next = $s.$p.val();)*] $($rest)*);
    };
    (@munch [$name:ident $pound:tt $attr:tt $s:ident] [$($done:tt)*]) => {
        impl Logic for $name {
            $pound $attr
            fn update(&mut $s) {
                $($done)*
            }
        }
    };
}

use super::*;

fn row(size: &str, product: Product, weight_lb_ft: f64) -> &'static PipeSize {
    find_row(size, Some(product), Some(weight_lb_ft)).unwrap()
}

#[test]
fn the_spot_values_are_the_standards() {
    // API 5CT: 9-5/8 in 47.00 lb/ft casing, 244.5 mm OD, 0.472 in (11.99 mm) wall, 69.94 kg/m.
    let casing = row("9-5/8", Product::Casing, 47.0);
    assert!((casing.outer_diameter_m - 0.2445).abs() < 5e-5, "{}", casing.outer_diameter_m);
    assert!((casing.wall_m - 0.011_99).abs() < 5e-6, "{}", casing.wall_m);
    assert!((casing.mass_per_length_kg_m - 69.94).abs() < 0.005);
    // API 5DP: 5 in 19.50 lb/ft drill pipe, 0.362 in (9.19 mm) wall.
    let pipe = row("5", Product::DrillPipe, 19.5);
    assert!((pipe.wall_m - 0.009_19).abs() < 5e-6, "{}", pipe.wall_m);
    assert!((pipe.outer_diameter_m - 0.127).abs() < 5e-5);
    // The collar: 6-1/2 in, about 137 kg/m.
    let collar = pipe_size("6-1/2").unwrap();
    assert_eq!(collar.product, Product::DrillCollar);
    assert!((collar.mass_per_length_kg_m - 137.0).abs() < 1.0, "{}", collar.mass_per_length_kg_m);
}

#[test]
fn every_plain_end_weight_is_the_steel_tube_of_its_section() {
    // w = ρ π (D² − d²) / 4, ρ = 7850 kg/m³, against the tabulated plain-end weight: within the
    // tables' rounding (0.005 lb/ft), their US-customary constants (10.69 or 10.68 for ρ π / 4,
    // 0.1 %) and the SI outside diameter's rounding to 0.1 mm (0.1 % on the smallest tube).
    for p in PIPE_CATALOGUE {
        let d_in = p.inner_diameter_m();
        let steel = STEEL_DENSITY_KG_M3 * std::f64::consts::FRAC_PI_4 * (p.outer_diameter_m.powi(2) - d_in * d_in);
        let tabulated = p.plain_end_kg_m();
        assert!(
            (tabulated - steel).abs() <= 0.005 * LB_FT_KG_M + 2e-3 * steel,
            "{}: tabulated {tabulated:.3} kg/m, steel tube {steel:.3} kg/m",
            p.label()
        );
    }
}

#[test]
fn every_nominal_weight_carries_its_connections_and_reads_the_same_in_both_units() {
    for p in PIPE_CATALOGUE {
        // The nominal (threaded and coupled, or label) weight is the plain tube's plus a share
        // of its couplings or tool joints and upsets: a few per cent to a fifth more.
        // A collar has no connection of its own: its weight is the plain bar's, to the whole lb/ft.
        let ratio = p.nominal_weight_lb_ft / p.plain_end_weight_lb_ft;
        let most = match p.product {
            Product::Casing | Product::Tubing => 1.10,
            Product::DrillPipe => 1.15,
            Product::HeavyWeightDrillPipe => 1.25,
            Product::DrillCollar => 1.0 + 0.5 / p.plain_end_weight_lb_ft,
        };
        assert!((0.98..=most).contains(&ratio), "{}: nominal / plain end = {ratio:.3}", p.label());
        let converted = p.nominal_weight_lb_ft * LB_FT_KG_M;
        assert!((p.mass_per_length_kg_m - converted).abs() <= 0.011, "{}: {} kg/m", p.label(), p.mass_per_length_kg_m);
        assert!(p.wall_m > 0.0 && 2.0 * p.wall_m < p.outer_diameter_m, "{}", p.label());
    }
}

#[test]
fn every_size_and_product_has_one_default_weight() {
    for size in sizes() {
        for product in Product::ALL {
            let rows: Vec<_> = PIPE_CATALOGUE.iter().filter(|p| p.size == size && p.product == product).collect();
            let defaults = rows.iter().filter(|p| p.default).count();
            assert!(rows.is_empty() || defaults == 1, "{size} {}: {defaults} defaults", product.name());
        }
    }
}

#[test]
fn a_size_alone_reads_as_the_old_catalogue() {
    // The rows and joint lengths the four-row catalogue had (the shipped scenarios' strings).
    for (size, od, wall_in, kg_m, length) in [
        ("2-3/8", 0.0603, 0.190, 7.00, 12.5),
        ("2-7/8", 0.0730, 0.217, 9.67, 12.5),
        ("3-1/2", 0.0889, 0.254, 13.84, 12.5),
        ("4-1/2", 0.1143, 0.250, 17.26, 11.6),
    ] {
        let s = PipeString::from_spec(&StringSpec::of_size(size)).unwrap();
        assert_eq!(s.pipe.outer_diameter_m, od, "{size}");
        assert_eq!(s.pipe.wall_m, wall_in * INCH_M, "{size}");
        assert_eq!(s.pipe.mass_per_length_kg_m, kg_m, "{size}");
        assert_eq!(s.length_m, length, "{size}");
        assert_eq!(s.mass_kg(), kg_m * length, "{size}");
        assert!(s.connections.is_empty());
    }
}

#[test]
fn the_seed_strings_weigh_what_the_paper_says() {
    // The seed: a 2-7/8 in string of about 121 kg and a 4-1/2 in string of about 200 kg.
    let tubing = PipeString::from_spec(&StringSpec::of_size("2-7/8")).unwrap();
    let casing = PipeString::from_spec(&StringSpec::of_size("4-1/2")).unwrap();
    assert!((tubing.mass_kg() - 121.0).abs() < 1.0, "{}", tubing.mass_kg());
    assert!((casing.mass_kg() - 200.0).abs() < 1.0, "{}", casing.mass_kg());
}

#[test]
fn bad_names_list_what_is_allowed() {
    let e = pipe_size("2-1/2").unwrap_err().to_string();
    assert!(e.contains("2-7/8") && e.contains("payload.size") && e.contains("13-3/8"), "{e}");
    let e = find_row("9-5/8", None, Some(46.0)).unwrap_err().to_string();
    assert!(e.contains("payload.weight_lb_ft") && e.contains("47.00"), "{e}");
    let e = find_row("9-5/8", Some(Product::DrillPipe), None).unwrap_err().to_string();
    assert!(e.contains("payload.product") && e.contains("casing"), "{e}");
    let spec = StringSpec { grade: Some("G105".into()), ..StringSpec::of_size("9-5/8") };
    let e = PipeString::from_spec(&spec).unwrap_err().to_string();
    assert!(e.contains("payload.grade") && e.contains("L80"), "{e}");
    let spec = StringSpec { joints: Some(4), ..StringSpec::of_size("9-5/8") };
    assert!(PipeString::from_spec(&spec).unwrap_err().to_string().contains("payload.joints"));
    let spec = StringSpec { range: Some(Range::R1), ..StringSpec::of_size("6-1/2") };
    assert!(PipeString::from_spec(&spec).unwrap_err().to_string().contains("R2"));
    let spec = StringSpec { joint_length_m: Some(16.0), ..StringSpec::of_size("9-5/8") };
    assert!(PipeString::from_spec(&spec).unwrap_err().to_string().contains("14.63"));
    let spec = StringSpec { length_m: Some(12.0), joints: Some(2), ..StringSpec::of_size("9-5/8") };
    assert!(PipeString::from_spec(&spec).unwrap_err().to_string().contains("payload.length_m"));
}

#[test]
fn grades_give_their_minimum_yield() {
    let spec = StringSpec { grade: Some("L80".into()), weight_lb_ft: Some(47.0), ..StringSpec::of_size("9-5/8") };
    let s = PipeString::from_spec(&spec).unwrap();
    // 80 ksi = 551.6 MPa.
    assert!((s.pipe.yield_strength_pa.unwrap() - 80e3 * 6894.757).abs() < 1e6);
    let spec = StringSpec { grade: Some("S135".into()), product: Some(Product::DrillPipe), ..StringSpec::of_size("5") };
    assert!((PipeString::from_spec(&spec).unwrap().pipe.yield_strength_pa.unwrap() - 135e3 * 6894.757).abs() < 1e6);
}

#[test]
fn a_stand_weighs_its_joints_and_connections_summed_by_hand() {
    // Three R2 joints of 5 in 19.50 drill pipe (8.69 m): the plain tube, a tool joint's pin part
    // at the near end, a whole tool joint at each of the two joints' meetings, a box at the far end.
    let spec = StringSpec {
        product: Some(Product::DrillPipe),
        range: Some(Range::R2),
        joints: Some(3),
        ..StringSpec::of_size("5")
    };
    let s = PipeString::from_spec(&spec).unwrap();
    let row = s.pipe.row.unwrap();
    let tj = row.connection;
    let (l, body) = (8.69, row.plain_end_kg_m());
    assert!((s.length_m - 3.0 * l).abs() < 1e-12);
    let total = 3.0 * (body * l + tj.added_mass_kg);
    assert!((s.mass_kg() - total).abs() < 1e-9 * total, "{} vs {total}", s.mass_kg());
    // Centre of mass, summed by hand: pins lead each joint, boxes trail it.
    let (pin, bx) = (tj.pin_length_m, tj.length_m - tj.pin_length_m);
    let per_m = tj.added_mass_kg / tj.length_m;
    let mut moment = body * 3.0 * l * 1.5 * l;
    for k in 0..3 {
        let start = k as f64 * l;
        moment += per_m * pin * (start + 0.5 * pin) + per_m * bx * (start + l - 0.5 * bx);
    }
    assert!((s.mass_centre_m() - moment / total).abs() < 1e-9, "{} vs {}", s.mass_centre_m(), moment / total);
    assert_eq!(s.connections.len(), 4);
}

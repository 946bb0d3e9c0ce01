use super::*;

fn all_configs() -> Vec<DialectConfig> {
    vec![
        DialectConfig::new(Dialect::Fanuc, GCodeSystem::A, MachineKind::Lathe),
        DialectConfig::new(Dialect::Fanuc, GCodeSystem::B, MachineKind::Lathe),
        DialectConfig::new(Dialect::Fanuc, GCodeSystem::C, MachineKind::Lathe),
        DialectConfig::new(Dialect::Osp, GCodeSystem::A, MachineKind::Lathe),
        DialectConfig::new(Dialect::Osp, GCodeSystem::A, MachineKind::MachiningCentre),
    ]
}

#[test]
fn tables_load_and_every_schema_name_resolves() {
    for (text, dialect) in [(FANUC_TOML, Dialect::Fanuc), (OSP_TOML, Dialect::Osp)] {
        let raw: RawDialect = toml::from_str(text).unwrap_or_else(|e| panic!("{dialect:?}: {e}"));
        for g in &raw.g {
            // A cycle's F and S are either the modal ones or its own; no default, so that a
            // new cycle says which.
            let cycle = matches!(g.kind, GKind::Cycle | GKind::LapCall);
            assert_eq!(
                g.feed_and_speed.is_some(),
                cycle,
                "{dialect:?}: G entry {:?} ({}) {} `feed_and_speed`",
                g.code,
                g.meaning,
                if cycle { "is a cycle and lacks" } else { "is no cycle and has" }
            );
            if let Some(schema) = &g.schema {
                assert!(
                    raw.schema.contains_key(schema),
                    "{dialect:?}: G entry {:?} names missing schema {schema}",
                    g.code
                );
            }
        }
        for (name, schema) in &raw.schema {
            for form in &schema.form {
                for key in form.m_words.keys() {
                    assert!(key.parse::<u16>().is_ok(), "{name}: m_words key {key}");
                }
            }
        }
    }
    for config in all_configs() {
        let tables = tables(config);
        assert!(tables.g(Code::whole(0)).is_some(), "{config:?} lacks G00");
        assert!(tables.address(Address::X).is_some());
    }
}

#[test]
fn g_code_systems_move_the_single_cycles_and_the_clamp() {
    let a = tables(all_configs()[0]);
    let b = tables(all_configs()[1]);
    let c = tables(all_configs()[2]);
    let schema_name =
        |t: &Tables, code: u16| t.g(Code::whole(code)).and_then(|g| g.schema).map(|s| t.schema(s).name.clone());
    assert_eq!(schema_name(a, 92).as_deref(), Some("thread_cycle"));
    assert_eq!(schema_name(b, 92).as_deref(), Some("coordinate_set_or_clamp"));
    assert_eq!(schema_name(c, 73).as_deref(), Some("stock_removal_turning"));
    assert_eq!(schema_name(b, 78).as_deref(), Some("thread_cycle"));
    assert!(a.g(Code::whole(91)).is_none());
    assert!(a.g_elsewhere(Code::whole(91)).is_some());
}

#[test]
fn osp_machine_kinds_split_the_shared_numbers() {
    let lathe = tables(all_configs()[3]);
    let mc = tables(all_configs()[4]);
    assert_eq!(lathe.g(Code::whole(81)).map(|g| g.kind), Some(GKind::LapMarker));
    assert_eq!(mc.g(Code::whole(81)).map(|g| g.kind), Some(GKind::Cycle));
    assert!(lathe.g(Code::whole(56)).is_none());
    assert!(lathe.g_elsewhere(Code::whole(56)).is_some());
    assert!(lathe.keyword(b"BHC").is_none());
    assert!(mc.keyword(b"BHC").is_some());
    assert!(lathe.extended_address(b"XA").is_some());
}

#[test]
fn address_round_trips_through_its_name() {
    for name in ["X", "Z", "XA", "OG", "TG"] {
        let address: Address = name.parse().unwrap();
        assert_eq!(address.name(), name);
    }
    assert_eq!(Code(121).display('G'), "G12.1");
    assert_eq!(Code::whole(1).display('G'), "G01");
}

//! Every pass's declared descriptor layout equals what naga reflected from its shaders, and
//! every compiled shader module belongs to some pass.

use ssgi::passes::all_layouts;
use ssgi::shaders::{DescriptorKind, ReflectedBinding, ALL};
use ssgi::vk::pipeline::check_bindings;

#[test]
fn every_pass_layout_matches_reflection() {
    for layout in all_layouts() {
        check_bindings(layout.pass, &layout.modules, &layout.declared)
            .unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn every_shader_module_is_used_by_a_pass() {
    let layouts = all_layouts();
    for module in ALL {
        let used = layouts
            .iter()
            .any(|l| l.modules.iter().any(|m| std::ptr::eq(*m, *module)));
        assert!(used, "{} is compiled but no pass uses it", module.label());
    }
}

#[test]
fn a_wrong_declaration_is_rejected() {
    let layout = all_layouts()
        .into_iter()
        .find(|l| l.pass == "direct")
        .unwrap();
    let mut wrong: Vec<ReflectedBinding> = layout.declared.to_vec();
    wrong.last_mut().unwrap().kind = DescriptorKind::SampledImage;
    let err = check_bindings(layout.pass, &layout.modules, &wrong).unwrap_err();
    assert!(err.to_string().contains("direct"), "{err}");
    let missing = &layout.declared[..layout.declared.len() - 1];
    assert!(check_bindings(layout.pass, &layout.modules, missing).is_err());
}

#[test]
fn compute_modules_have_workgroups_and_graphics_do_not() {
    for m in ALL {
        let wg: u32 = m.workgroup_size.iter().product();
        match m.stage {
            ssgi::shaders::ShaderStage::Compute => assert!(wg > 0, "{}", m.label()),
            _ => assert_eq!(wg, 0, "{}", m.label()),
        }
        assert_eq!(m.spirv.len() % 4, 0);
        assert_eq!(
            &m.spirv[..4],
            &0x0723_0203u32.to_le_bytes(),
            "{} SPIR-V magic",
            m.label()
        );
    }
}

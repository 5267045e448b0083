//! The GPU can be opened (or the test says loudly why not).

use srt_gpu::context_or_skip;

#[test]
fn opens_an_adapter() {
    let Some(context) = context_or_skip("opens_an_adapter") else {
        return;
    };
    println!("adapter: {}", context.adapter_summary());
    assert!(!context.adapter_info.name.is_empty());
    context.take_errors().unwrap();
}

use super::*;

#[test]
fn the_page_embeds_its_data_and_the_bundle_without_a_network_reference() {
    let mut frames = FrameColumns { scale: "full", ..FrameColumns::default() };
    frames.time.push(1.5);
    let page = html(&PageData::Replay { title: "a </script> & b", frames: &frames }).unwrap();
    assert!(page.contains("<title>a &lt;/script&gt; &amp; b — crane viewer</title>"));
    // The title inside the JSON cannot close the data element early.
    assert!(
        page.contains(r#"{"mode":"replay","title":"a <\/script> & b","frames":{"scale":"full","time":[1.5],"#),
        "{page}"
    );
    assert_eq!(page.matches("</script>").count(), 2);
    assert!(page.contains(BUNDLE));
    // No favicon request either: the browser would ask the live server, or the file system.
    assert!(page.contains("<link rel=\"icon\" href=\"data:,\">"));
    assert!(!page.contains("src=\"http") && !page.contains("href=\"http"));
}

#[test]
fn the_bundle_cannot_end_its_script_element_early() {
    assert!(!BUNDLE.contains("</script"));
}

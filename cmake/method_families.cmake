# shaftlab_method_family(TARGET HEADER FUNCTION): a folder's methods join the method table
# (frame/method_registry.h). TARGET is the library that holds them, HEADER (from the project root)
# declares FUNCTION, a `void FUNCTION(sl::frame::MethodRegistry&)` that adds them. methods/ links
# every such library and generates the table's source from these lines, so adding a method
# touches its own folder and nothing else (docs/adding-a-method.md).
function(shaftlab_method_family target header function)
    set_property(GLOBAL APPEND PROPERTY SHAFTLAB_METHOD_FAMILIES "${target}|${header}|${function}")
endfunction()

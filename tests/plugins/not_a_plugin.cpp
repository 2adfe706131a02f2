// A shared module that is not an nsbench plugin: it exports no nsbench_plugin_abi_version.
extern "C" int not_a_plugin_answer() { return 42; }

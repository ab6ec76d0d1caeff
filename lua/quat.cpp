namespace rigidlab::lua { }

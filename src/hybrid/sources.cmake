# sources of src/hybrid
